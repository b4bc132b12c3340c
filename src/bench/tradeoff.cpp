#include "bench/tradeoff.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bench/bench_scene.hpp"
#include "bench/read_back.hpp"
#include "bench/timed_run.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"

#include "bench/number_text.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

using bench_text::exact;
using io::format_significant;

// Scene overrides shared by every run of one experiment: stop after the peak and `cycles`
// stick-slip cycles; no series (the loading branch the fit needs is kept regardless).
std::vector<std::string> run_overrides(double stop_time, int cycles) {
  return {set_number("stop.time", stop_time), "stop.cycles=" + std::to_string(cycles), "stop.at_first_peak=false",
          "output.series=[]"};
}

WorkPrecisionRow make_row(const std::string& experiment, const std::string& method, double setting, const TimedRun& t) {
  WorkPrecisionRow r;
  r.experiment = experiment;
  r.method = method;
  r.setting = setting;
  r.wall_s = t.wall_s;
  r.cpu_s = t.cpu_s;
  r.repeats = t.repeats;
  r.t_end = t.obs.t_end;
  r.steps = t.obs.steps;
  r.value = robust_values(t.obs);
  return r;
}

}  // namespace

TradeoffResult run_tradeoff(const TradeoffOptions& opt) {
  TradeoffResult res;
  auto log = [&](const std::string& s) {
    if (opt.log) *opt.log << s << std::flush;
  };
  const std::vector<std::string> base = run_overrides(opt.stop_time, opt.cycles);
  auto scene_with = [&](const fs::path& path, std::vector<std::string> base_o, std::vector<std::string> extra) {
    base_o.insert(base_o.end(), extra.begin(), extra.end());
    return bench_scene(path, base_o);
  };
  const Scene probe = scene_with(opt.scene, base, {});
  const std::string name = probe.experiment.name;
  res.stand_in = is_stand_in(probe.experiment);

  // Converged solution and its check.
  log("converged: event, tolerance " + format_significant(opt.converged_tolerance) + " ... ");
  const TimedRun conv = timed_run(
      scene_with(opt.scene, base, {"solver.method=event", set_number("solver.tolerance", opt.converged_tolerance)}),
      opt.repeats);
  log(format_significant(conv.wall_s, 3) + " s, t_end = " + format_significant(conv.obs.t_end) + " s, " +
      std::to_string(conv.obs.ss_cycles) + " cycles\n");
  const Observables& ref_obs = conv.obs;

  auto add = [&](const std::string& method, double setting, const TimedRun& t) {
    WorkPrecisionRow r = make_row(name, method, setting, t);
    r.error = relative_errors(t.obs, ref_obs);
    std::string line = "  " + method + " " + format_significant(setting) + ": wall " + format_significant(r.wall_s, 3) +
                       " s (" + std::to_string(r.repeats) + " runs), errors";
    for (std::size_t i = 0; i < n_robust; ++i)
      line += " " + robust_names()[i] + " " + format_significant(r.error[i], 2);
    log(line + "\n");
    res.rows.push_back(r);
    if (opt.on_setting) opt.on_setting(res.rows.size(), 2 + opt.tolerances.size() + opt.Ct.size());
  };
  add("event", opt.converged_tolerance, conv);
  log("check: event, tolerance " + format_significant(opt.check_tolerance) + "\n");
  add("event", opt.check_tolerance,
      timed_run(
          scene_with(opt.scene, base, {"solver.method=event", set_number("solver.tolerance", opt.check_tolerance)}),
          opt.repeats));

  for (double tol : opt.tolerances)
    add("event", tol,
        timed_run(scene_with(opt.scene, base, {"solver.method=event", set_number("solver.tolerance", tol)}),
                  opt.repeats));
  std::vector<const WorkPrecisionRow*> ref_rows;
  for (double Ct : opt.Ct) {
    log("reference, C_t = " + format_significant(Ct) + " ...\n");
    add("reference", Ct,
        timed_run(scene_with(opt.scene, base, {"solver.method=reference", set_number("solver.Ct", Ct)}), opt.repeats));
  }
  for (const auto& r : res.rows)
    if (r.method == "reference") ref_rows.push_back(&r);
  for (std::size_t j = 0; j + 1 < ref_rows.size(); ++j)
    for (std::size_t i = 0; i < n_robust; ++i) {
      const auto& lo = *ref_rows[j];
      const auto& hi = *ref_rows[j + 1];
      res.orders.push_back({robust_names()[i], lo.setting, hi.setting,
                            std::log(lo.error[i] / hi.error[i]) / std::log(hi.setting / lo.setting)});
    }

  return res;
}

std::string work_precision_csv(const std::vector<WorkPrecisionRow>& rows) {
  std::ostringstream o;
  o << "experiment,method,setting,wall_s,cpu_s,repeats,t_end_s,steps";
  for (const auto& n : robust_names()) o << ",value_" << n;
  for (const auto& n : robust_names()) o << ",relerr_" << n;
  o << '\n';
  for (const auto& r : rows) {
    o << io::csv_field(r.experiment) << ',' << io::csv_field(r.method) << ',' << format_significant(r.setting) << ','
      << format_significant(r.wall_s, 4) << ',' << format_significant(r.cpu_s, 4) << ',' << r.repeats << ','
      << format_significant(r.t_end, 10) << ',' << r.steps;
    for (double x : r.value) o << ',' << exact(x);
    for (double x : r.error) o << ',' << format_significant(x, 4);
    o << '\n';
  }
  return o.str();
}

std::vector<WorkPrecisionRow> read_work_precision_csv(const fs::path& csv, std::vector<int>* lines) {
  const io::TextTable t = read_bench_csv(csv, "asperity bench tradeoff");
  std::vector<WorkPrecisionRow> rows;
  for (std::size_t i = 0; i < t.size(); ++i) {
    WorkPrecisionRow r;
    r.experiment = t.text(i, "experiment");
    r.method = t.text(i, "method");
    if (r.method != "reference" && r.method != "event") t.fail(i, "method", "expected reference or event");
    r.setting = t.number(i, "setting");
    r.wall_s = t.number(i, "wall_s");
    r.cpu_s = t.number(i, "cpu_s");
    r.repeats = read_repeats(t, i);
    r.t_end = t.number(i, "t_end_s");
    r.steps = t.count(i, "steps");
    for (std::size_t k = 0; k < n_robust; ++k) {
      r.value[k] = t.measured(i, "value_" + robust_names()[k]);
      r.error[k] = t.measured(i, "relerr_" + robust_names()[k]);
    }
    rows.push_back(std::move(r));
    if (lines) lines->push_back(t.line(i));
  }
  return rows;
}

namespace {

std::string order_csv(const std::vector<OrderRow>& rows) {
  std::ostringstream o;
  o << "observable,Ct_lo,Ct_hi,order\n";
  for (const auto& r : rows)
    o << r.observable << ',' << format_significant(r.Ct_lo) << ',' << format_significant(r.Ct_hi) << ','
      << format_significant(r.order, 3) << '\n';
  return o.str();
}

// Six log-log panels, error against wall time, one curve per method; errors below 1e-16
// (or exactly 0) are drawn at 1e-16. Only the two ends of each curve carry their setting (the
// inner ones crowd on the steep event curve); the key names the range, under each panel (inside,
// any corner meets a curve or an end label on some data). The panels are 5 % shorter and raised,
// so that the lower right key clears the stand-in mark in the corner below it; each y range
// reaches 5 % beyond the data, so that an end label on a decade is not cut by the border.
std::string plot_script(const TradeoffResult& r) {
  std::ostringstream gp;
  std::string range[2];
  for (const std::string method : {"reference", "event"}) {
    gp << "$" << method << " << EOD\n";
    std::vector<const WorkPrecisionRow*> rows;
    for (const auto& row : r.rows) {
      bool all_zero = true;  // the converged run itself
      for (double e : row.error) all_zero = all_zero && e == 0.0;
      if (row.method == method && !all_zero) rows.push_back(&row);
    }
    // Coarse to fine: C_t up, tolerance down.
    std::sort(rows.begin(), rows.end(), [&](auto* a, auto* b) {
      return method == "reference" ? a->setting < b->setting : a->setting > b->setting;
    });
    std::ostringstream ends;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& row = *rows[i];
      std::ostringstream line;
      line << format_significant(row.wall_s, 6) << ' ' << format_significant(row.setting);
      for (double e : row.error) line << ' ' << format_significant(std::isfinite(e) ? std::max(e, 1e-16) : NAN, 6);
      gp << line.str() << '\n';
      if (i == 0 || i + 1 == rows.size()) ends << line.str() << '\n';
    }
    gp << "EOD\n$" << method << "_ends << EOD\n" << ends.str() << "EOD\n";
    if (!rows.empty())
      range[method == "event"] = format_significant(rows.front()->setting) +
                                 (rows.size() > 1 ? " … " + format_significant(rows.back()->setting) : "");
  }
  const std::string exp = r.rows.empty() ? "" : r.rows.front().experiment;
  gp << stand_in_mark(r.stand_in) << "set multiplot layout 2,3 scale 1, 0.95 offset 0, 0.012 title "
     << gnuplot_text("Work-precision on bench experiment " + exp +
                     " (60 junctions): error vs converged event run (tol 1e-12)")
     << "\n"
     << "set logscale xy\nset offsets 0, 0, graph 0.05, graph 0.05\n"
     << "set format y '10^{%T}'\nset format x '10^{%T}'\nset grid\n"
     << "set xlabel 'wall time [s]'\nset ylabel 'relative error [1]'\nset key bmargin center horizontal font ',9'\n";
  for (std::size_t i = 0; i < n_robust; ++i) {
    const int c = static_cast<int>(i) + 3;
    gp << "set title " << gnuplot_quote(column_symbol(robust_names()[i])) << "\n"
       << "plot $reference using 1:" << c << " with linespoints pt 7 ps 0.6 lw 1.5 title "
       << gnuplot_quote("reference, C_t " + range[0]) << ", "
       << "$reference_ends using 1:" << c << ":(sprintf('%g',$2)) with labels right offset -1,0 font ',8' notitle, "
       << "$event using 1:" << c << " with linespoints pt 5 ps 0.6 lw 1.5 title "
       << gnuplot_quote("event, tol " + range[1]) << ", "
       << "$event_ends using 1:" << c << ":(sprintf('%g',$2)) with labels left offset 1,0 font ',8' notitle\n";
  }
  gp << "unset multiplot\n";
  return gp.str();
}

bool draw_tradeoff(const fs::path& dir, const TradeoffResult& r, const FigureFormats& figures, std::string* error) {
  return render_figures(dir / "work_precision.png", plot_script(r), 1500, 900, figures, error);
}

}  // namespace

void write_tradeoff(const fs::path& dir, const TradeoffResult& r, const FigureFormats& figures) {
  fs::create_directories(dir);
  io::write_text_file(dir / "work_precision.csv", work_precision_csv(r.rows));
  io::write_text_file(dir / "reference_order.csv", order_csv(r.orders));
  TradeoffResult drawn;
  drawn.stand_in = r.stand_in;
  drawn.rows = r.rows.empty() ? r.rows : read_work_precision_csv(dir / "work_precision.csv");
  draw_tradeoff(dir, drawn, figures, nullptr);
}

bool redraw_tradeoff(const fs::path& dir, const fs::path& scene, const FigureFormats& figures, std::string* error) {
  const fs::path csv = dir / "work_precision.csv";
  std::vector<int> lines;
  TradeoffResult r;
  r.rows = read_work_precision_csv(csv, &lines);
  // The stand-in flag as run_tradeoff sets it: is_stand_in of the scene's experiment.
  const Experiment e = bench_scene(scene, {}).experiment;
  r.stand_in = is_stand_in(e);
  for (std::size_t i = 0; i < r.rows.size(); ++i)
    if (r.rows[i].experiment != e.name)
      throw io::InputError(io::input_path(csv), lines[i], "experiment",
                           io::quote(r.rows[i].experiment) + " is not the experiment of " + scene.generic_string() +
                               " (" + io::quote(e.name) + "): pass the scene the bench ran with --scene");
  check_redraw_targets(dir / "work_precision.png", figures);
  return draw_tradeoff(dir, r, figures, error);
}

}  // namespace asperity
