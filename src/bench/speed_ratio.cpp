#include "bench/speed_ratio.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bench/bench_scene.hpp"
#include "bench/number_text.hpp"
#include "bench/timed_run.hpp"
#include "io/atomic_file.hpp"
#include "io/numbers.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

using io::format_significant;

// NaN-propagating max over errors [from, to).
double max_error(const std::array<double, n_robust>& e, std::size_t from, std::size_t to) {
  double m = 0;
  for (std::size_t i = from; i < to; ++i) {
    if (std::isnan(e[i])) return e[i];
    m = std::max(m, e[i]);
  }
  return m;
}

std::string describe(const SpeedRun& r) {
  return r.method + (r.method == "event" ? " tol " : " C_t ") + format_significant(r.setting) +
         (r.whole ? "" : " (window)");
}

}  // namespace

double SpeedRun::max_loading_error() const { return max_error(error, 0, 4); }
double SpeedRun::max_stick_slip_error() const { return max_error(error, 4, n_robust); }

bool SpeedRun::at_least_as_accurate_as(const SpeedRun& other) const {
  // A NaN error of `other` (e.g. no stick-slip cycle at all) counts as the worst.
  for (std::size_t i = 0; i < n_robust; ++i)
    if (!(error[i] <= other.error[i]) && !(std::isfinite(error[i]) && std::isnan(other.error[i]))) return false;
  return true;
}

double SpeedComparison::ratio_wall() const {
  return (reference.wall_s / reference.t_end) / (event.wall_s / event.t_end);
}
double SpeedComparison::ratio_cpu() const { return (reference.cpu_s / reference.t_end) / (event.cpu_s / event.t_end); }

namespace {

// The scenes, the log and the record of one speed comparison; `truth` is set by run_truth and
// every whole run's errors are measured against it.
struct SpeedBench {
  const SpeedOptions& opt;
  SpeedResult& res;
  TimedRun truth;

  void log(const std::string& s) const {
    if (opt.log) *opt.log << s << std::flush;
  }
  // Every run stops after the peak and `cycles` cycles (a window: at its end); no series (the
  // loading branch is kept regardless).
  Scene scene(double stop_time, int cycles, std::vector<std::string> extra) const {
    std::vector<std::string> o{set_number("stop.time", stop_time), "stop.cycles=" + std::to_string(cycles),
                               "stop.at_first_peak=false", "output.series=[]"};
    o.insert(o.end(), extra.begin(), extra.end());
    return bench_scene(opt.scene, o);
  }
  Scene event_scene(double tol) const {
    return scene(opt.stop_time, opt.cycles, {"solver.method=event", set_number("solver.tolerance", tol)});
  }
  Scene reference_scene(double Ct, bool whole) const {
    // A whole reference run spans the truth's T_run (a coarse C_t may lose the stick-slip and
    // run on to stop_time otherwise): the same simulated span as the run extrapolated to.
    return whole ? scene(res.T_run, opt.cycles, {"solver.method=reference", set_number("solver.Ct", Ct)})
                 : scene(opt.window_s, -1, {"solver.method=reference", set_number("solver.Ct", Ct)});
  }
  SpeedRun record(const std::string& method, double setting, bool whole, const TimedRun& t) const;
};

SpeedRun SpeedBench::record(const std::string& method, double setting, bool whole, const TimedRun& t) const {
  SpeedRun r;
  r.method = method;
  r.setting = setting;
  r.whole = whole;
  r.t_end = t.obs.t_end;
  r.wall_s = t.wall_s;
  r.cpu_s = t.cpu_s;
  r.steps = t.obs.steps;
  r.cycles = t.obs.ss_cycles;
  r.repeats = t.repeats;
  r.error.fill(std::nan(""));
  if (whole) r.error = relative_errors(t.obs, truth.obs);
  std::string line = "  " + describe(r) + ": " + format_significant(r.wall_s, 4) + " s wall, " +
                     format_significant(r.cpu_s, 4) + " s CPU (" + std::to_string(r.repeats) + " runs), " +
                     std::to_string(r.steps) + " steps, t_end " + format_significant(r.t_end, 6) + " s";
  if (whole)
    line += ", " + std::to_string(r.cycles) + " cycles, max error loading " +
            format_significant(r.max_loading_error(), 2) + ", stick-slip " +
            format_significant(r.max_stick_slip_error(), 2);
  log(line + "\n");
  return r;
}

// The truth: a tight event run through the whole run.
void run_truth(SpeedBench& b) {
  const SpeedOptions& opt = b.opt;
  b.log("truth: event, tolerance " + format_significant(opt.truth_tolerance) + " ... ");
  b.truth = timed_run(b.event_scene(opt.truth_tolerance), 1);
  b.res.experiment = b.scene(opt.stop_time, opt.cycles, {}).experiment.name;
  b.res.T_run = b.truth.obs.t_end;
  b.log(format_significant(b.truth.wall_s, 3) + " s, t_end " + format_significant(b.res.T_run) + " s, " +
        std::to_string(b.truth.obs.ss_cycles) + " cycles\n");
  b.res.truth = b.record("event", opt.truth_tolerance, true, b.truth);
}

// Event solver: the scene's own tolerance (`ev_default`), then the accuracy ladder; returns every
// event run, loosest tolerance first.
std::vector<SpeedRun> run_event_ladder(SpeedBench& b, SpeedRun& ev_default) {
  const SpeedOptions& opt = b.opt;
  const double default_tol = b.scene(opt.stop_time, opt.cycles, {}).solver.tolerance;  // the shipped default
  ev_default = b.record("event", default_tol, true, timed_run(b.event_scene(default_tol), opt.repeats));
  b.res.runs.push_back(ev_default);
  std::vector<SpeedRun> ladder;
  for (double tol : opt.event_tolerances)
    ladder.push_back(b.record("event", tol, true, timed_run(b.event_scene(tol), opt.repeats)));
  b.res.runs.insert(b.res.runs.end(), ladder.begin(), ladder.end());
  ladder.push_back(ev_default);
  std::sort(ladder.begin(), ladder.end(), [](const SpeedRun& a, const SpeedRun& b) { return a.setting > b.setting; });
  return ladder;
}

// Reference: whole runs at the coarse C_t (returned, coarsest first), the early window at target
// and first coarse C_t (`window_target`), and the per-step cost ratios they give.
std::vector<SpeedRun> run_reference(SpeedBench& b, SpeedRun& window_target) {
  const SpeedOptions& opt = b.opt;
  SpeedResult& res = b.res;
  std::vector<SpeedRun> whole;
  for (double Ct : opt.whole_run_Ct) {
    b.log("reference, C_t = " + format_significant(Ct) + ", whole run ...\n");
    whole.push_back(b.record("reference", Ct, true, timed_run(b.reference_scene(Ct, true), opt.repeats)));
  }
  b.log("reference, early window of " + format_significant(opt.window_s) + " s ...\n");
  window_target = b.record("reference", opt.target_Ct, false, timed_run(b.reference_scene(opt.target_Ct, false), 1));
  const SpeedRun window_coarse = b.record("reference", opt.whole_run_Ct.front(), false,
                                          timed_run(b.reference_scene(opt.whole_run_Ct.front(), false), opt.repeats));
  res.runs.insert(res.runs.end(), whole.begin(), whole.end());
  res.runs.push_back(window_target);
  res.runs.push_back(window_coarse);
  res.dt_target = window_target.t_end / static_cast<double>(window_target.steps);
  res.target_steps = static_cast<std::int64_t>(std::ceil(res.T_run / res.dt_target - 1e-9));
  if (whole.size() >= 2) res.whole_per_step_ratio = whole[1].cpu_per_step() / whole[0].cpu_per_step();
  res.window_per_step_ratio = window_target.cpu_per_step() / window_coarse.cpu_per_step();
  return whole;
}

// The reference at the paper's C_t, not run: the per-step cost of the finest whole run `ref` times
// the step count at target_Ct.
SpeedRun extrapolated_reference(const SpeedOptions& opt, const SpeedResult& res, const SpeedRun& ref) {
  SpeedRun extrapolated = ref;
  extrapolated.setting = opt.target_Ct;
  extrapolated.steps = res.target_steps;
  extrapolated.t_end = static_cast<double>(res.target_steps) * res.dt_target;
  extrapolated.wall_s = ref.wall_per_step() * static_cast<double>(res.target_steps);
  extrapolated.cpu_s = ref.cpu_per_step() * static_cast<double>(res.target_steps);
  extrapolated.error.fill(std::nan(""));  // not run: its accuracy is not measured here
  return extrapolated;
}

// The comparisons. The measured reference is the finest whole run.
void add_comparisons(const SpeedOptions& opt, SpeedResult& res, const std::vector<SpeedRun>& whole,
                     const std::vector<SpeedRun>& ladder, const SpeedRun& ev_default, const SpeedRun& window_target) {
  const SpeedRun& ref = whole.back();
  res.comparisons.push_back(
      {"whole run: reference at C_t " + format_significant(ref.setting) + " vs event at its default tolerance",
       "measured, both over the whole run", ref, ev_default});
  const SpeedRun* matched = nullptr;  // loosest tolerance at least as accurate as the reference
  for (const SpeedRun& e : ladder)
    if (e.at_least_as_accurate_as(ref)) {
      matched = &e;
      break;
    }
  if (matched)
    res.comparisons.push_back({"whole run at equal accuracy: reference at C_t " + format_significant(ref.setting) +
                                   " vs the loosest event tolerance at least as accurate on all six observables",
                               "measured, both over the whole run", ref, *matched});
  res.comparisons.push_back(
      {"whole run: reference at C_t " + format_significant(opt.target_Ct) + " vs event at its default tolerance",
       "reference extrapolated: per-step cost of its whole run at C_t " + format_significant(ref.setting) +
           " x the step count at C_t " + format_significant(opt.target_Ct) +
           " (T_run/dt, T_run of the tight "
           "event run); per-step CPU cost vs C_t: whole run at C_t " +
           format_significant(opt.whole_run_Ct.back()) + " / at " + format_significant(opt.whole_run_Ct.front()) +
           " = " + format_significant(res.whole_per_step_ratio, 3) + ", first " + format_significant(opt.window_s) +
           " s at C_t " + format_significant(opt.target_Ct) + " / at " + format_significant(opt.whole_run_Ct.front()) +
           " = " + format_significant(res.window_per_step_ratio, 3) + "; its accuracy is not measured; event measured",
       extrapolated_reference(opt, res, ref), ev_default});
  res.comparisons.push_back(
      {"early window (the previous definition): reference at C_t " + format_significant(opt.target_Ct) +
           " over its first " + format_significant(opt.window_s) + " s vs event over the whole run",
       "measured; the window (every junction bisected) is not representative of the run", window_target, ev_default});
}

}  // namespace

SpeedResult run_speed(const SpeedOptions& opt) {
  SpeedResult res;
  res.threads = omp_get_max_threads();
  SpeedBench bench{opt, res, {}};
  run_truth(bench);
  SpeedRun ev_default, window_target;
  const std::vector<SpeedRun> ladder = run_event_ladder(bench, ev_default);
  const std::vector<SpeedRun> whole = run_reference(bench, window_target);
  add_comparisons(opt, res, whole, ladder, ev_default, window_target);
  return res;
}

namespace {

std::string errors_text(const SpeedRun& r) {
  return bench_text::exact(r.max_loading_error()) + ',' + bench_text::exact(r.max_stick_slip_error());
}

}  // namespace

std::string speed_runs_csv(const SpeedResult& r) {
  std::ostringstream o;
  o << "experiment,method,setting,span,t_end_s,steps,cycles,repeats,wall_s,cpu_s,wall_per_step_s,cpu_per_step_s";
  for (const auto& n : robust_names()) o << ",relerr_" << n;
  o << '\n';
  auto row = [&](const SpeedRun& x) {
    o << r.experiment << ',' << x.method << ',' << format_significant(x.setting) << ','
      << (x.whole ? "whole run" : "window") << ',' << format_significant(x.t_end, 8) << ',' << x.steps << ','
      << x.cycles << ',' << x.repeats << ',' << format_significant(x.wall_s, 4) << ',' << format_significant(x.cpu_s, 4)
      << ',' << format_significant(x.wall_per_step(), 4) << ',' << format_significant(x.cpu_per_step(), 4);
    for (double e : x.error) o << ',' << format_significant(e, 3);
    o << '\n';
  };
  row(r.truth);
  for (const auto& x : r.runs) row(x);
  return o.str();
}

std::string speed_ratio_csv(const SpeedResult& r) {
  std::ostringstream o;
  o << "experiment,comparison,basis,reference_Ct,reference_span,reference_steps,reference_t_end_s,reference_wall_s,"
       "reference_cpu_s,"
       "reference_max_error_loading,reference_max_error_stick_slip,event_tolerance,event_t_end_s,event_wall_s,"
       "event_cpu_s,event_max_error_loading,event_max_error_stick_slip,ratio_wall,ratio_cpu\n";
  auto quoted = [](const std::string& s) { return '"' + s + '"'; };
  for (const auto& c : r.comparisons) {
    const SpeedRun &a = c.reference, &b = c.event;
    o << r.experiment << ',' << quoted(c.comparison) << ',' << quoted(c.basis) << ',' << format_significant(a.setting)
      << ',' << (a.whole ? "whole run" : "window") << ',' << a.steps << ',' << format_significant(a.t_end, 6) << ','
      << format_significant(a.wall_s, 4) << ',' << format_significant(a.cpu_s, 4) << ',' << errors_text(a) << ','
      << format_significant(b.setting) << ',' << format_significant(b.t_end, 6) << ','
      << format_significant(b.wall_s, 4) << ',' << format_significant(b.cpu_s, 4) << ',' << errors_text(b) << ','
      << format_significant(c.ratio_wall(), 3) << ',' << format_significant(c.ratio_cpu(), 3) << '\n';
  }
  return o.str();
}

void write_speed(const fs::path& dir, const SpeedResult& r) {
  fs::create_directories(dir);
  io::write_text_file(dir / "speed_ratio.csv", speed_ratio_csv(r));
  io::write_text_file(dir / "speed_runs.csv", speed_runs_csv(r));
}

}  // namespace asperity
