// asperity plot STORE --x KEY --y KEY [--z OBSERVABLE] [--where COL=VALUE]... [--out FILE.png|svg|pdf] [--format F]
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "report/heatmap.hpp"
#include "report/line_plot.hpp"
#include "report/plot_axes.hpp"

namespace asperity::cli {

Command add_plot_command(CLI::App& app) {
  struct Args {
    std::string store, out, format;
    HeatmapOptions h;
    bool quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("plot",
                                     "Heat map of a sweep store column over two others (--z), or a line "
                                     "plot over one (no --z), one line per experiment");
  sub->add_option("store", a->store, "Store folder (results/<campaign>)")->required();
  sub->add_option("--x", a->h.x, "Column on the x axis, e.g. model.eta")->required();
  sub->add_option("--y", a->h.y, "Column on the y axis, e.g. model.epsilon (heat map) or ss_drop (line plot)")
      ->required();
  sub->add_option("--z", a->h.z, "Column shown as colour, e.g. ss_drop (omit it for a line plot of --y over --x)");
  sub->add_option("--where,-w", a->h.where, "Keep points with COLUMN=VALUE (repeatable), e.g. experiment=P4.00N")
      ->allow_extra_args(false);
  sub->add_option("--out,-o", a->out,
                  "Figure file, .png, .svg or .pdf (default STORE/heatmap_<z>_over_<x>_<y>.png "
                  "or STORE/line_<y>_over_<x>.png); its gnuplot script is kept beside it as .gp");
  sub->add_option("--format", a->format, "Figure format when --out is not given")
      ->check(CLI::IsMember({"png", "svg", "pdf"}));
  add_quiet_flag(sub, a->quiet);
  return Command{
      sub, [a](const Invocation&) {
        namespace fs = std::filesystem;
        const auto with_format = [&](const std::string& stem) {
          return a->out.empty() && !a->format.empty() ? fs::path(a->store) / (stem + "." + a->format)
                                                      : fs::path(a->out);
        };
        if (a->h.z.empty()) {  // a line plot of --y over --x
          LinePlotOptions l{a->h.x, a->h.y, a->h.where, {}};
          l.out = with_format("line_" + plot_detail::file_part(l.y) + "_over_" + plot_detail::file_part(l.x));
          const LinePlotReport r = plot_lines(a->store, l);
          if (!a->quiet)
            std::printf("%s: %zu lines, %zu points, %zu blank%s\n", r.figure.string().c_str(), r.lines, r.points,
                        r.blank, r.used_grid.empty() ? "" : (" (grid " + r.used_grid + ")").c_str());
          return exit_ok;
        }
        a->h.out = with_format("heatmap_" + plot_detail::file_part(a->h.z) + "_over_" + plot_detail::file_part(a->h.x) +
                               "_" + plot_detail::file_part(a->h.y));
        const HeatmapReport r = plot_heatmap(a->store, a->h);
        if (!a->quiet)
          std::printf("%s: %zu cells, %zu blank%s\n", r.png.string().c_str(), r.cells, r.blank,
                      r.used_grid.empty() ? "" : (" (grid " + r.used_grid + ")").c_str());
        return exit_ok;
      }};
}

}  // namespace asperity::cli
