// asperity plot STORE --x KEY --y KEY --z OBSERVABLE [--where COL=VALUE]... [--out FILE.png]
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "report/heatmap.hpp"

namespace asperity::cli {

Command add_plot_command(CLI::App& app) {
  struct Args {
    std::string store, out;
    HeatmapOptions h;
    bool quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("plot", "Heat map (PNG) of a sweep store column over two others");
  sub->add_option("store", a->store, "Store folder (results/<campaign>)")->required();
  sub->add_option("--x", a->h.x, "Column on the x axis, e.g. model.eta")->required();
  sub->add_option("--y", a->h.y, "Column on the y axis, e.g. model.epsilon")->required();
  sub->add_option("--z", a->h.z, "Column shown as colour, e.g. ss_drop")->required();
  sub->add_option("--where,-w", a->h.where, "Keep points with COLUMN=VALUE (repeatable), e.g. experiment=P4.00N")
      ->allow_extra_args(false);
  sub->add_option("--out,-o", a->out, "PNG file (default STORE/heatmap_<z>_over_<x>_<y>.png)");
  add_quiet_flag(sub, a->quiet);
  return Command{sub, [a](const Invocation&) {
                   a->h.out = a->out;
                   const HeatmapReport r = plot_heatmap(a->store, a->h);
                   if (!a->quiet)
                     std::printf("%s: %zu cells, %zu blank%s\n", r.png.string().c_str(), r.cells, r.blank,
                                 r.used_grid.empty() ? "" : (" (grid " + r.used_grid + ")").c_str());
                   return exit_ok;
                 }};
}

}  // namespace asperity::cli
