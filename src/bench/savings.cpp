#include "bench/savings.hpp"

#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <system_error>

#include "bench/bench_scene.hpp"
#include "bench/read_back.hpp"
#include "bench/timed_run.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "observe/simulate.hpp"
#include "report/gnuplot.hpp"
#include "report/run_writer.hpp"

#include "bench/number_text.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

using io::format_significant;

// Median time of writing the run directory of `scene` (what `asperity run` does after the
// integration) into `scratch`.
double write_time(const Scene& scene, const fs::path& scratch, int repeats) {
  const RunResult r = simulate(scene);
  std::vector<double> ts;
  for (int i = 0; i < repeats; ++i) {
    const fs::path dir = scratch / ("run" + std::to_string(i));
    const auto t0 = std::chrono::steady_clock::now();
    write_run(dir, scene, r.obs, r.recorder);
    ts.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  return median(ts);
}

}  // namespace

std::vector<SavingRow> run_savings(const SavingsOptions& opt) {
  std::vector<SavingRow> rows;
  const fs::path scratch = opt.scratch.empty() ? fs::temp_directory_path() / "asperity-bench-savings" : opt.scratch;
  fs::create_directories(scratch);
  struct Case {
    const char* saving;
    const char* variant;
    bool baseline;
    std::vector<std::string> extra;
  };
  const std::vector<Case> cases{
      {"series", "all series columns", true, {}},
      {"series", "output.series=[]", false, {"output.series=[]"}},
      {"stop", "peak + 5 cycles", true, {"output.series=[]"}},
      {"stop", "stop.at_first_peak=true", false, {"output.series=[]", "stop.at_first_peak=true"}},
      {"area_law", "alpha_b=7.25e-16", true, {"output.series=[]", "model.alpha_b=7.25e-16"}},
      {"area_law", "alpha_b=0 (linear)", false, {"output.series=[]", "model.alpha_b=0"}},
  };
  for (const fs::path& path : opt.scenes) {
    for (std::size_t c = 0; c + 1 < cases.size(); c += 2) {
      auto scene_of = [&](const Case& k) {
        std::vector<std::string> o = opt.overrides;
        o.insert(o.end(), k.extra.begin(), k.extra.end());
        return bench_scene(path, o);
      };
      const Scene sa = scene_of(cases[c]), sb = scene_of(cases[c + 1]);
      const auto [ta, tb] = timed_pair(sa, sb, opt.repeats);
      for (int j = 0; j < 2; ++j) {
        const Case& k = cases[c + static_cast<std::size_t>(j)];
        const TimedRun& t = j == 0 ? ta : tb;
        const Scene& scene = j == 0 ? sa : sb;
        SavingRow r;
        r.experiment = scene.experiment.name;
        r.stand_in = is_stand_in(scene.experiment);
        r.saving = k.saving;
        r.variant = k.variant;
        r.baseline = k.baseline;
        r.wall_s = t.wall_s;
        r.cpu_s = t.cpu_s;
        r.repeats = t.repeats;
        r.t_end = t.obs.t_end;
        r.steps = t.obs.steps;
        r.force_evals = t.obs.force_evals;
        r.series_bytes = t.series_bytes;
        r.write_s = write_time(scene, scratch, opt.repeats);
        rows.push_back(r);
        if (opt.log)
          *opt.log << "  " << r.experiment << " (stand-in) " << r.saving << ": " << r.variant << ": integrate "
                   << format_significant(r.wall_s * 1e3, 4) << " ms wall (" << format_significant(r.cpu_s * 1e3, 4)
                   << " ms CPU) + write " << format_significant(r.write_s * 1e3, 4) << " ms, t_end "
                   << format_significant(r.t_end, 5) << " s, series " << r.series_bytes << " B\n"
                   << std::flush;
      }
    }
  }
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return rows;
}

std::string savings_csv(const std::vector<SavingRow>& rows) {
  std::ostringstream o;
  o << "experiment,saving,variant,baseline,wall_s,cpu_s,write_s,total_s,repeats,t_end_s,steps,force_evals,series_"
       "bytes\n";
  for (const auto& r : rows)
    o << io::csv_field(r.experiment) << ',' << io::csv_field(r.saving) << ',' << io::csv_field(r.variant) << ','
      << (r.baseline ? "yes" : "no") << ',' << format_significant(r.wall_s, 4) << ',' << format_significant(r.cpu_s, 4)
      << ',' << format_significant(r.write_s, 4) << ',' << format_significant(r.total_s(), 4) << ',' << r.repeats << ','
      << format_significant(r.t_end, 6) << ',' << r.steps << ',' << r.force_evals << ',' << r.series_bytes << '\n';
  return o.str();
}

std::vector<SavingRow> read_savings_csv(const fs::path& csv, std::vector<int>* lines) {
  const io::TextTable t = read_bench_csv(csv, "asperity bench savings");
  std::vector<SavingRow> rows;
  for (std::size_t i = 0; i < t.size(); ++i) {
    SavingRow r;
    r.experiment = t.text(i, "experiment");
    r.saving = t.text(i, "saving");
    r.variant = t.text(i, "variant");
    r.baseline = t.yes_no(i, "baseline");
    r.wall_s = t.number(i, "wall_s");
    r.cpu_s = t.number(i, "cpu_s");
    r.write_s = t.number(i, "write_s");
    t.number(i, "total_s");  // wall_s + write_s, checked as a number and recomputed
    r.repeats = read_repeats(t, i);
    r.t_end = t.number(i, "t_end_s");
    r.steps = t.count(i, "steps");
    r.force_evals = t.count(i, "force_evals");
    r.series_bytes = static_cast<std::size_t>(t.count(i, "series_bytes"));
    rows.push_back(std::move(r));
    if (lines) lines->push_back(t.line(i));
  }
  return rows;
}

namespace {

// Bar chart of the first scene: baseline and variant side by side per saving, in ms of CPU
// time (integration + writing): on a shared machine the wall time also measures the others.
std::string savings_script(const std::vector<SavingRow>& rows) {
  const std::string exp = rows.front().experiment;
  std::ostringstream gp;
  gp << "$d << EOD\n";
  for (std::size_t i = 0; i + 1 < rows.size(); i += 2) {
    if (rows[i].experiment != exp) break;
    gp << '"' << rows[i].saving << "\\n"
       << rows[i + 1].variant << "\\nvs " << rows[i].variant << "\" "
       << format_significant((rows[i].cpu_s + rows[i].write_s) * 1e3, 5) << ' '
       << format_significant((rows[i + 1].cpu_s + rows[i + 1].write_s) * 1e3, 5) << '\n';
  }
  gp << "EOD\n"
     << stand_in_mark(rows.front().stand_in) << "set title " << gnuplot_text("Model only what a scene requires: " + exp)
     << " . \"\\n\" . " << gnuplot_quote("CPU time of integration + writing the run directory") << "\n"
     << "set style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
     << "set xtics noenhanced\n"  // the tic labels are scene settings (output.series=[]), not markup
     << "set bmargin 5\nset boxwidth 0.9\nset ylabel 'CPU time [ms]'\nset grid ytics\nset yrange [0:*]\nset key top "
        "right\n"
     << tics_for_span("y", "$d", "($2 > $3 ? $2 : $3)", true)
     << "plot $d using 2:xticlabels(1) title 'baseline' lc rgb '#4477aa', "
        "'' using 3 title 'variant (saving)' lc rgb '#ee6677'\n";
  return gp.str();
}

// Page width for SVG and PDF (over 1,000 pixels): three clustered bars with two-line scene
// settings under them do not fit a column.
bool draw_savings(const fs::path& dir, const std::vector<SavingRow>& rows, const FigureFormats& figures,
                  std::string* error) {
  return render_figures(dir / "savings.png", savings_script(rows), 1200, 600, figures, error);
}

}  // namespace

void write_savings(const fs::path& dir, const std::vector<SavingRow>& rows, const FigureFormats& figures) {
  fs::create_directories(dir);
  io::write_text_file(dir / "savings.csv", savings_csv(rows));
  if (rows.empty()) return;
  std::vector<SavingRow> drawn = read_savings_csv(dir / "savings.csv");
  for (std::size_t i = 0; i < drawn.size(); ++i) drawn[i].stand_in = rows[i].stand_in;
  draw_savings(dir, drawn, figures, nullptr);
}

bool redraw_savings(const fs::path& dir, const std::vector<fs::path>& scenes, const FigureFormats& figures,
                    std::string* error) {
  std::vector<int> lines;
  std::vector<SavingRow> rows = read_savings_csv(dir / "savings.csv", &lines);
  // The stand-in flag as run_savings sets it: is_stand_in of the scene's experiment.
  std::map<std::string, bool> stand_in;
  std::string given;
  for (const fs::path& path : scenes) {
    const Scene scene = bench_scene(path, {});
    stand_in[scene.experiment.name] = is_stand_in(scene.experiment);
    given += (given.empty() ? "" : ", ") + path.generic_string();
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto it = stand_in.find(rows[i].experiment);
    if (it == stand_in.end())
      throw io::InputError(io::input_path(dir / "savings.csv"), lines[i], "experiment",
                           io::quote(rows[i].experiment) + " is the experiment of none of the scenes (" + given +
                               "): pass those the bench ran with --scene");
    rows[i].stand_in = it->second;
  }
  check_redraw_targets(dir / "savings.png", figures);
  return draw_savings(dir, rows, figures, error);
}

}  // namespace asperity
