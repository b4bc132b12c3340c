#include "fit/fit.hpp"

#include <Eigen/Dense>
#include <nlopt.hpp>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

#include "batch/parallel_runner.hpp"
#include "batch/stop_flag.hpp"
#include "fit/fit_journal.hpp"
#include "fit/objective.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "observe/simulate.hpp"

namespace asperity {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string g6(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// One experiment run at given settings: its residual and what the report needs.
struct ExperimentEval {
  double residual = Observables::nan;
  Observables obs;
  std::vector<Sample> loading;
  double mass_kg = 0;
  bool stand_in = false;
  std::optional<MeasuredCurve> measured;
  JointTerms terms;
  std::vector<Sample> series;
  std::string error;  // empty: ran
};

// RunInterrupted (the stop's) passes through: the evaluation is abandoned, not failed.
using UserTerm = std::function<double(const FitExperiment&, const Scene&, const RunResult&)>;

ExperimentEval run_experiment(const FitSpec& spec, std::size_t e, const std::vector<SceneSetting>& settings,
                              bool keep, const RunMonitor* monitor, const UserTerm* user_term) {
  omp_set_num_threads(1);  // this task is one of `threads` workers: no nested OpenMP team
  ExperimentEval out;
  try {
    const FitExperiment& fe = spec.experiments[e];
    const Scene scene = fe.scene.build(settings);
    RunResult r = simulate(scene, 0, monitor);
    if (spec.objective == FitObjective::user) {
      if (!user_term || !*user_term) throw std::invalid_argument("run_fit: the user objective needs FitOptions::user_term");
      out.residual = (*user_term)(fe, scene, r);
    } else if (spec.objective == FitObjective::area_and_force) {
      out.terms = area_and_force_terms(scene, r.obs, r.recorder.loading_branch(), r.recorder.series(), fe, spec.noise, spec.force_score);
      out.residual = out.terms.total();
    } else {
      out.residual = experiment_residual(spec.objective, scene, r.obs, r.recorder.loading_branch(), fe.target);
    }
    if (std::isnan(out.residual) && spec.objective == FitObjective::user) {
      out.error = "objective term of " + fe.name + " is NaN (the user objective returned nan)";
    } else if (std::isnan(out.residual)) {
      out.error = "objective term of " + fe.name + " is NaN (model alpha = " + g6(r.obs.alpha) +
                  ", measured alpha = " + g6(r.obs.alpha_measured) + ", Q_s = " + g6(r.obs.Q_s) +
                  ", loading-branch points = " + std::to_string(r.recorder.loading_branch().size()) + ")";
    } else if (!r.obs.peak_found && spec.objective != FitObjective::area_and_force) {
      // (area_and_force compares the whole measured Q(t) window, peak or not: a model without a
      // peak there is a poor fit, scored as such, not a broken run.)
      // Without a confirmed peak, Q_s, the loading branch and every objective built on them
      // come from wherever the run stopped: a number, but not the one the fit is about.
      out.error = fe.name + " (" + display_path(scene.experiment.file) +
                  "): no confirmed static friction peak before stop.time = " + g6(scene.stop.time) +
                  " s (highest Q " + g6(r.obs.Q_s) + " N at t = " + g6(r.obs.t_peak) +
                  " s); the objective would use an unfinished loading branch: raise stop.time";
    }
    if (keep) {
      out.obs = r.obs;
      out.loading = r.recorder.loading_branch();
      out.mass_kg = scene.experiment.mass_kg;
      out.stand_in = scene.experiment.description.find("STAND-IN") != std::string::npos;
      out.measured = scene.experiment.measured;
      if (spec.objective == FitObjective::area_and_force) out.series = r.recorder.series();
    }
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception& ex) {
    out.error = spec.experiments[e].name + ": " + ex.what();
  }
  return out;
}

// Evaluations answered from the journal and computed, over the whole fit.
struct Counts {
  std::atomic<int> replayed{0}, computed{0};
};

struct Problem {
  const FitSpec* spec = nullptr;
  std::string label;  // the optimization's label (journal key with `part`)
  std::string part;   // "fit", "profile" or "refit KEY SIGN" (fit_journal.hpp)
  std::vector<std::size_t> exps;
  std::vector<FreeVariable> vars;
  std::vector<std::vector<SceneSetting>> extra;  // per exps[k]: fixed shifts (error bars)
  std::vector<Evaluation> log;
  std::string failure;
  Clock::time_point t0;
  const std::function<void(const FitTick&)>* on_evaluation = nullptr;  // FitOptions::on_evaluation
  std::atomic<int>* ticked = nullptr;  // evaluations told to on_evaluation for this optimization
  FitJournal* journal = nullptr;                               // FitOptions::journal
  bool replay_only = false;                                    // FitOptions::replay_only
  Counts* counts = nullptr;
  std::string not_journaled;  // replay_only: the evaluation the journal lacked
  const StopFlag* stop = nullptr;     // FitOptions::stop, polled by every run
  const UserTerm* user_term = nullptr;  // FitOptions::user_term
  bool interrupted = false;           // the stop ended the optimization
};

// Tells FitOptions::on_evaluation that an evaluation of the optimization is done.
void tick(const Problem& pb, const char* part, double objective) {
  if (pb.ticked) ++*pb.ticked;
  if (pb.on_evaluation && *pb.on_evaluation) (*pb.on_evaluation)(FitTick{&pb.label, part, objective, 0});
}

std::vector<SceneSetting> settings_for(const Problem& pb, std::size_t k, const std::vector<double>& x) {
  std::vector<SceneSetting> s = pb.extra[k];
  for (std::size_t i = 0; i < pb.vars.size(); ++i) {
    const FreeVariable& v = pb.vars[i];
    if (v.experiment < 0 || static_cast<std::size_t>(v.experiment) == pb.exps[k])
      s.push_back({pb.spec->parameters[v.parameter].key, x[i]});
  }
  return s;
}

// All experiments of the problem at x (in parallel); the objective is their sum in order.
Evaluation evaluate(const Problem& pb, const std::vector<double>& x, std::vector<ExperimentEval>* runs = nullptr) {
  const auto t0 = Clock::now();
  std::vector<ExperimentEval> r(pb.exps.size());
  // Isolated: a thread waiting here runs only these runs, never another task's optimizer (so
  // each nlopt::opt stays on its own thread, with no nested optimize on one stack).
  for_each_nested(pb.exps.size(), [&](std::size_t k) {
    r[k] = run_experiment(*pb.spec, pb.exps[k], settings_for(pb, k, x), runs != nullptr, pb.stop ? pb.stop->monitor() : nullptr,
                          pb.user_term);
  }, Nesting::isolated);
  Evaluation ev;
  ev.values = x;
  ev.objective = 0;
  for (const auto& e : r) {
    ev.residuals.push_back(e.residual);
    ev.objective += e.residual;
    if (!e.error.empty() && ev.status == "ok") ev.status = e.error;
  }
  if (ev.status == "ok" && !std::isfinite(ev.objective)) ev.status = "objective is not finite: " + g6(ev.objective);
  if (ev.status != "ok") ev.objective = Observables::nan;
  ev.wall_s = seconds_since(t0);
  if (runs) *runs = std::move(r);
  return ev;
}

// every_digit: the shortest text that reads back exactly (a failure may hang on the exact point).
std::string values_text(const Problem& pb, const std::vector<double>& x, bool every_digit = false) {
  std::string s;
  for (std::size_t i = 0; i < x.size(); ++i)
    s += (i ? ", " : "") + pb.vars[i].label + " = " + (every_digit ? scene_io::format_double(x[i]) : g6(x[i]));
  return s;
}

// evaluate() through the journal: an evaluation of this (part, optimization) journaled at exactly
// x is returned as it was (no model run; also a point NLopt asks for twice in one run, which the
// deterministic model would give again anyway); a new one is appended as soon as it finishes.
// Without the journal entry in replay_only mode: nullopt (the caller stops).
std::optional<Evaluation> evaluate_journaled(const Problem& pb, int index, const std::vector<double>& x) {
  if (pb.journal) {
    if (std::optional<Evaluation> ev = pb.journal->find(pb.part, pb.label, x)) {
      ev->index = index;
      if (pb.counts) ++pb.counts->replayed;
      return ev;
    }
    if (pb.replay_only) return std::nullopt;
  }
  Evaluation ev = evaluate(pb, x);
  ev.index = index;
  if (pb.journal) pb.journal->append(pb.part, pb.label, ev);
  if (pb.counts) ++pb.counts->computed;
  return ev;
}

std::string not_journaled_text(const Problem& pb, int index, const std::vector<double>& x) {
  return "evaluation " + std::to_string(index) + " of " + pb.part + " " + pb.label + " (" + values_text(pb, x) +
         ") is in no journal";
}

double nlopt_objective(unsigned n, const double* u, double* /*grad: derivative-free*/, void* data) {
  Problem& pb = *static_cast<Problem*>(data);
  std::vector<double> x(n);
  for (unsigned i = 0; i < n; ++i) {
    const FitParameter& p = pb.spec->parameters[pb.vars[i].parameter];
    x[i] = parameter_value(p, u[i]);
    assert(x[i] >= p.lo && x[i] <= p.hi);
  }
  const int index = static_cast<int>(pb.log.size()) + 1;
  // NLopt's wrapper turns any exception of ours into a result code: the stop is carried past it
  // in the problem, as the replay's NotJournaled is.
  std::optional<Evaluation> journaled;
  try {
    if (pb.stop && pb.stop->requested()) throw RunInterrupted("stopped");  // a run too short to poll would go on
    journaled = evaluate_journaled(pb, index, x);
  } catch (const RunInterrupted&) {
    pb.interrupted = true;
    throw nlopt::forced_stop();
  }
  if (!journaled) {
    pb.not_journaled = not_journaled_text(pb, index, x);
    throw nlopt::forced_stop();
  }
  const Evaluation& ev = *journaled;
  pb.log.push_back(ev);
  tick(pb, pb.part.rfind("refit", 0) == 0 ? "refit" : "fit", ev.objective);
  if (ev.status != "ok") {
    // Every digit: a solver failure may hang on the exact point (the 6-digit rounding ran through).
    pb.failure = "evaluation " + std::to_string(ev.index) + " (" + values_text(pb, x, true) + "): " + ev.status;
    throw nlopt::forced_stop();  // caught by NLopt's C++ wrapper, rethrown by optimize()
  }
  return ev.objective;
}

struct OptimizeResult {
  std::vector<double> best;
  double objective = Observables::nan;
  std::string stop_reason, failure;
  std::vector<Evaluation> log;
  double wall_s = 0;
};

// One NLopt run of `algorithm` on the problem from scaled point u (updated to where it ended).
std::string nlopt_stage(Problem& pb, const std::string& algorithm, int max_evaluations, std::vector<double>& u,
                        const std::vector<double>& start, double initial_step, std::string& failure) {
  const FitSpec& spec = *pb.spec;
  const auto n = static_cast<unsigned>(pb.vars.size());
  nlopt::opt opt(static_cast<nlopt::algorithm>(nlopt_algorithm_from_string(algorithm.c_str())), n);
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  std::vector<double> xtol(n), step(n, initial_step);
  for (unsigned i = 0; i < n; ++i) {
    const FitParameter& p = spec.parameters[pb.vars[i].parameter];
    // xtol_rel on x → absolute on the scaled coordinate: Δu = Δx/x / ln(hi/lo) (log scale),
    // Δu = xtol_rel·|x_ref| / (hi − lo) (linear, x_ref = start, or the larger bound if 0).
    const double ref = start[i] != 0 ? std::abs(start[i]) : std::max(std::abs(p.lo), std::abs(p.hi));
    xtol[i] = p.log_scale ? spec.xtol_rel / std::log(p.hi / p.lo) : spec.xtol_rel * ref / (p.hi - p.lo);
  }
  opt.set_xtol_abs(xtol);
  if (spec.ftol_rel > 0) opt.set_ftol_rel(spec.ftol_rel);
  if (spec.ftol_abs > 0) opt.set_ftol_abs(spec.ftol_abs);
  opt.set_maxeval(max_evaluations);
  opt.set_initial_step(step);
  opt.set_min_objective(nlopt_objective, &pb);
  double f = 0;
  std::string reason;
  try {
    // One evaluation of a local algorithm is the objective at the start: NLopt's BOBYQA would
    // first move a start lying within its initial step of a bound, and evaluate there instead.
    // (A global one, DIRECT, keeps its own first point: the box's centre.)
    if (max_evaluations == 1 && algorithm.rfind("LN_", 0) == 0) {
      nlopt_objective(n, u.data(), nullptr, &pb);
      return nlopt_result_name(nlopt::MAXEVAL_REACHED);
    }
    reason = nlopt_result_name(opt.optimize(u, f));
  } catch (const nlopt::forced_stop&) {
    reason = "FORCED_STOP";
    failure = pb.failure.empty() ? "NLopt forced stop" : pb.failure;
  } catch (const nlopt::roundoff_limited&) {
    reason = "ROUNDOFF_LIMITED";  // best point so far is still the answer
  } catch (const std::exception& e) {
    reason = "FAILURE";
    failure = std::string("NLopt: ") + e.what();
  }
  return reason;
}

// Runs the optimization's problem (Problem::part set) from `start`: the algorithm, then the
// polish stage from its best point when the spec has one (`polish_only`: the polish alone, or
// the algorithm when there is none). NotJournaled when replay_only and an evaluation was not
// journaled.
OptimizeResult optimize(Problem pb, const std::vector<double>& start, double initial_step, bool polish_only = false) {
  const FitSpec& spec = *pb.spec;
  const auto n = static_cast<unsigned>(pb.vars.size());
  OptimizeResult out;
  const auto t0 = Clock::now();
  std::vector<double> u(n);
  for (unsigned i = 0; i < n; ++i) u[i] = parameter_coordinate(spec.parameters[pb.vars[i].parameter], start[i]);
  const bool polish = !spec.polish_algorithm.empty();
  auto best_so_far = [&] {
    double fb = Observables::nan;
    std::vector<double> xb;
    for (const auto& ev : pb.log)
      if (ev.status == "ok" && !(ev.objective >= fb)) fb = ev.objective, xb = ev.values;
    return xb;
  };
  auto interrupted = [&] {
    if (pb.interrupted) throw RunInterrupted("fit interrupted in " + pb.part + " " + pb.label);
    if (!pb.not_journaled.empty()) throw NotJournaled(pb.not_journaled);
  };
  if (!(polish_only && polish)) {
    out.stop_reason = nlopt_stage(pb, spec.algorithm, spec.max_evaluations, u, start, initial_step, out.failure);
    interrupted();
  }
  if (polish && out.failure.empty()) {
    std::vector<double> from = polish_only ? start : best_so_far();
    if (!from.empty()) {
      for (unsigned i = 0; i < n; ++i) u[i] = parameter_coordinate(spec.parameters[pb.vars[i].parameter], from[i]);
      const std::string r = nlopt_stage(pb, spec.polish_algorithm, spec.polish_max_evaluations, u, from,
                                        polish_only ? initial_step : initial_step * 0.5, out.failure);
      out.stop_reason = polish_only ? r : out.stop_reason + ", then " + spec.polish_algorithm + " " + r;
      interrupted();
    }
  }
  out.wall_s = seconds_since(t0);
  for (const auto& ev : pb.log)
    if (ev.status == "ok" && !(ev.objective >= out.objective)) {
      out.objective = ev.objective;
      out.best = ev.values;
    }
  if (out.best.empty()) out.best.assign(n, Observables::nan);
  out.log = std::move(pb.log);
  return out;
}

// The optimization's problem as FitOptions asks for it: its part and journal, its experiments and
// free variables, no shifts.
Problem fit_problem(const FitSpec& spec, const FitOptions& options, const Optimization& o, Counts& counts,
                    const StopFlag& stop) {
  Problem pb;
  pb.stop = &stop;
  pb.spec = &spec;
  pb.label = o.label;
  pb.part = "fit";
  pb.journal = options.journal;
  pb.replay_only = options.replay_only;
  pb.counts = &counts;
  pb.exps = o.experiments;
  pb.vars = o.variables;
  pb.extra.assign(o.experiments.size(), {});
  pb.on_evaluation = &options.on_evaluation;
  pb.user_term = &options.user_term;
  return pb;
}

// The journal part of start k (0-based): the first keeps "fit", so journals of single-start fits
// replay as they always did.
std::string start_part(std::size_t k) { return k == 0 ? std::string("fit") : "fit start " + std::to_string(k + 1); }

// The points every start begins from, SI: the file's start, then Sobol points of the scaled box.
std::vector<std::vector<double>> start_points(const FitSpec& spec, const Optimization& o) {
  const std::size_t n = o.variables.size();
  std::vector<double> u0(n);
  for (std::size_t i = 0; i < n; ++i) u0[i] = parameter_coordinate(spec.parameters[o.variables[i].parameter], o.start[i]);
  std::vector<std::vector<double>> points{o.start};
  const std::size_t more = static_cast<std::size_t>(std::max(spec.starts, 1) - 1);
  for (const auto& u : sobol_starts(n, more, u0)) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = parameter_value(spec.parameters[o.variables[i].parameter], u[i]);
    points.push_back(std::move(x));
  }
  return points;
}

// Runs every start (in parallel, each its own Problem and journal part: the order of the
// evaluations inside a start is NLopt's, deterministic, whatever runs beside it) and puts them
// together into `o`: the best start's point, all evaluations numbered start after start, and
// the verdict on convergence.
void run_starts(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  const std::vector<std::vector<double>> from = start_points(spec, o);
  std::vector<OptimizeResult> results(from.size());
  for_each_nested(from.size(), [&](std::size_t k) {
    Problem q = pb;
    q.part = start_part(k);
    results[k] = k == 0 ? optimize(std::move(q), from[k], spec.initial_step)
                        : optimize(std::move(q), from[k], spec.initial_step, /*polish_only=*/true);
  });
  std::vector<StartEnd> ends;
  for (std::size_t k = 0; k < results.size(); ++k) {
    OptimizeResult& r = results[k];
    StartRun sr{start_part(k), from[k], r.best, r.objective, static_cast<int>(r.log.size()), r.stop_reason, r.failure, false};
    if (o.failure.empty() && !r.failure.empty()) o.failure = (k == 0 ? "" : "start " + std::to_string(k + 1) + ": ") + r.failure;
    StartEnd e{std::vector<double>(r.best.size()), r.objective};
    for (std::size_t i = 0; i < r.best.size(); ++i) e.u[i] = parameter_coordinate(spec.parameters[o.variables[i].parameter], r.best[i]);
    ends.push_back(std::move(e));
    for (Evaluation& ev : r.log) {
      ev.index = static_cast<int>(o.log.size()) + 1;
      o.log.push_back(std::move(ev));
    }
    o.starts.push_back(std::move(sr));
  }
  const ConvergenceVerdict v = judge_convergence(ends, BasinRule{spec.basin_tolerance, spec.basin_distance});
  for (std::size_t k = 0; k < o.starts.size(); ++k) o.starts[k].in_best_basin = v.in_best_basin[k];
  const StartRun& best = o.starts[v.best];
  o.best_start = v.best;
  o.best = best.best;
  o.objective = best.objective;
  o.stop_reason = best.stop_reason;
  o.evaluations = static_cast<int>(o.log.size());
  o.converged = v.converged;
  o.convergence = v.reason;
  o.in_best_basin = v.in_basin;
  o.spread = v.spread;
  o.wall_s = seconds_since(t0);
}

// The best runs, kept for the report (deterministic: same objective as journaled).
void keep_best_runs(const Problem& pb, Optimization& o) {
  std::vector<ExperimentEval> runs;
  const Evaluation ev = evaluate(pb, o.best, &runs);
  tick(pb, "best", ev.objective);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    ExperimentRun er;
    er.experiment = o.experiments[k];
    er.residual = runs[k].residual;
    er.obs = runs[k].obs;
    er.loading = std::move(runs[k].loading);
    er.mass_kg = runs[k].mass_kg;
    er.stand_in = runs[k].stand_in;
    er.measured = std::move(runs[k].measured);
    er.terms = runs[k].terms;
    er.series = std::move(runs[k].series);
    er.force = pb.spec->experiments[o.experiments[k]].force;
    o.best_runs.push_back(std::move(er));
  }
  if (ev.status != "ok" && o.failure.empty()) o.failure = "re-run at the optimum failed: " + ev.status;
  // A best taken from a journal line is only as good as that line: runs are deterministic, so
  // its re-run must give its objective (to rounding of the same binary on another core: bit
  // for bit in practice; 1e-9 leaves room for another libm). A line whose digest was recomputed
  // after an edit passes the journal's check but not this one.
  if (!pb.journal || ev.status != "ok") return;
  const double tol = 1e-9 * std::max(std::abs(ev.objective), std::abs(o.objective)) + 1e-300;
  if (std::abs(ev.objective - o.objective) <= tol) return;
  if (const auto at = pb.journal->where(pb.part, pb.label, o.best)) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "the journaled best evaluation of %s has objective %.10g but its re-run gives %.10g: the "
                  "line was edited or forged; remove it (or the folder) and rerun",
                  o.label.c_str(), o.objective, ev.objective);
    throw InputError(at->first, at->second, "objective", msg);
  }
}

// The objective along each profiled parameter around the optimum, the others at the optimum
// (in parallel, journaled; points of every profile share the part "profile": their values differ).
void run_profile(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  const ProfileSettings& ps = spec.profile_settings;
  const std::vector<std::size_t> which = ps.parameters.empty() ? std::vector<std::size_t>{ps.parameter} : ps.parameters;
  const std::size_t m = static_cast<std::size_t>(ps.points);
  std::vector<ParameterProfile> profiles(which.size());
  for (std::size_t q = 0; q < which.size(); ++q) {
    profiles[q].parameter = which[q];
    profiles[q].points.resize(m);
  }
  for_each_nested(which.size() * m, [&](std::size_t flat) {
    const std::size_t q = flat / m, i = flat % m;
    const FitParameter& p = spec.parameters[which[q]];
    ProfilePoint& pt = profiles[q].points[i];
    pt.factor = 1.0 + ps.span * (2.0 * static_cast<double>(i) / static_cast<double>(m - 1) - 1.0);
    std::vector<double> x = o.best;
    bool inside = true;
    for (std::size_t j = 0; j < x.size(); ++j)
      if (o.variables[j].parameter == which[q]) {
        x[j] = o.best[j] * pt.factor;
        pt.value = x[j];
        inside = inside && x[j] >= p.lo && x[j] <= p.hi;
      }
    if (!inside) {
      pt.status = "outside the bounds";
      return;
    }
    Problem qb = pb;
    qb.part = "profile";
    const int index = static_cast<int>(flat) + 1;
    const std::optional<Evaluation> ev = evaluate_journaled(qb, index, x);
    if (!ev) throw NotJournaled(not_journaled_text(qb, index, x));
    tick(qb, "profile", ev->objective);
    pt.objective = ev->objective;
    pt.status = ev->status;
  });
  o.profiles = std::move(profiles);
  o.profile_parameter = o.profiles.front().parameter;
  o.profile = o.profiles.front().points;
  o.profile_wall_s = seconds_since(t0);
}

// Where the profile rises by `rise` above `f0` on each side of the optimum (linear between
// points); NaN where it does not within the span.
void profile_interval(ParameterProfile& pp, double f0, double rise, double x0) {
  const auto& pts = pp.points;
  auto crossing = [&](int from, int step) {
    double xa = x0, fa = f0;
    for (int i = from; i >= 0 && i < static_cast<int>(pts.size()); i += step) {
      const ProfilePoint& p = pts[static_cast<std::size_t>(i)];
      if (p.status != "ok" || !std::isfinite(p.objective)) return Observables::nan;
      if (p.objective - f0 >= rise) return xa + (f0 + rise - fa) / (p.objective - fa) * (p.value - xa);
      xa = p.value, fa = p.objective;
    }
    return Observables::nan;
  };
  std::size_t mid = 0;  // the point nearest factor 1
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (std::abs(pts[i].factor - 1) < std::abs(pts[mid].factor - 1)) mid = i;
  const bool at_mid = std::abs(pts[mid].factor - 1) < 1e-12;
  const int left = static_cast<int>(mid) - (at_mid ? 1 : 0), right = static_cast<int>(mid) + (at_mid ? 1 : 0);
  double a = crossing(left, -1), b = crossing(right, +1);
  if (a > b) std::swap(a, b);
  pp.lo = a, pp.hi = b;
  // Least-squares parabola in d = value − x0 (scaled by the span; Eigen's QR).
  double span = 0;
  for (const ProfilePoint& p : pts) span = std::max(span, std::abs(p.value - x0));
  if (!(span > 0)) return;
  std::vector<const ProfilePoint*> ok;
  for (const ProfilePoint& p : pts)
    if (p.status == "ok" && std::isfinite(p.objective)) ok.push_back(&p);
  if (ok.size() < 3) return;
  Eigen::MatrixXd V(static_cast<Eigen::Index>(ok.size()), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(ok.size()));
  for (std::size_t r = 0; r < ok.size(); ++r) {
    const double d = (ok[r]->value - x0) / span;
    V.row(static_cast<Eigen::Index>(r)) << 1.0, d, d * d;
    y[static_cast<Eigen::Index>(r)] = ok[r]->objective - f0;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V);
  if (qr.rank() < 3) return;
  const double c2 = qr.solve(y)[2] / (span * span);  // back to SI
  if (c2 > 0) pp.parabola_sigma = std::sqrt(rise / c2);
}

// The Hessian's evaluations: objective values at points of the scaled coordinates u ∈ [0, 1]ⁿ,
// in parallel and journaled (part "hessian", numbered on).
struct HessianPoints {
  const FitSpec& spec;
  const Problem& pb;
  const Optimization& o;
  int counter = 0;  // evaluations so far

  void eval(const std::vector<std::vector<double>>& us, std::vector<double>& fv, std::vector<std::string>& st) {
    const std::size_t n = o.variables.size();
    fv.assign(us.size(), Observables::nan);
    st.assign(us.size(), "");
    const int base = counter;
    counter += static_cast<int>(us.size());
    for_each_nested(us.size(), [&](std::size_t k) {
      std::vector<double> x(n);
      for (std::size_t v = 0; v < n; ++v) x[v] = parameter_value(spec.parameters[o.variables[v].parameter], us[k][v]);
      Problem qb = pb;
      qb.part = "hessian";
      const int index = base + static_cast<int>(k) + 1;
      const std::optional<Evaluation> ev = evaluate_journaled(qb, index, x);
      if (!ev) throw NotJournaled(not_journaled_text(qb, index, x));
      tick(qb, "hessian", ev->objective);
      fv[k] = ev->objective;
      st[k] = ev->status;
    });
  }
};

// The optimum in scaled coordinates u0, the first steps h (hessian_step relative) and dx/du; an
// empty string, or why there is no central difference.
std::string hessian_start(const FitSpec& spec, const Optimization& o, std::vector<double>& u0, std::vector<double>& h,
                          std::vector<double>& dxdu) {
  const std::size_t n = o.variables.size();
  u0.resize(n), h.resize(n), dxdu.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const FitParameter& p = spec.parameters[o.variables[i].parameter];
    u0[i] = parameter_coordinate(p, o.best[i]);
    if (p.log_scale) {
      h[i] = spec.hessian_step / std::log(p.hi / p.lo);
      dxdu[i] = o.best[i] * std::log(p.hi / p.lo);
    } else {
      h[i] = spec.hessian_step * std::max(std::abs(o.best[i]), 0.01 * (p.hi - p.lo)) / (p.hi - p.lo);
      dxdu[i] = p.hi - p.lo;
    }
    if (u0[i] - h[i] < 0 || u0[i] + h[i] > 1)
      return o.variables[i].label + " = " + g6(o.best[i]) + " is within one step (" + g6(spec.hessian_step) +
             " relative) of its bound: no central difference";
  }
  return "";
}

// Steps: from hessian_step, rescaled (up to 4 rounds) until each parameter's own central rise
// (f(+h) + f(−h))/2 − f0 is within [1, 16] s² (target 4 s²: about two conditional standard
// deviations): large enough above rounding, small enough to stay quadratic where the objective is
// sharp (epsilon moves every stick-slip event). An empty string, or why not.
std::string settle_steps(HessianPoints& hp, const std::vector<double>& u0, std::vector<double>& h, double f0, double s2) {
  const std::size_t n = u0.size();
  const double target = 4 * s2;
  std::vector<bool> settled(n, false);
  for (int round = 0; round < 5; ++round) {
    std::vector<std::vector<double>> us;
    std::vector<std::size_t> who;
    for (std::size_t i = 0; i < n; ++i) {
      if (settled[i]) continue;
      for (const int sg : {-1, +1}) {
        std::vector<double> u = u0;
        u[i] += sg * h[i];
        us.push_back(u);
      }
      who.push_back(i);
    }
    if (who.empty()) break;
    std::vector<double> fv;
    std::vector<std::string> st;
    hp.eval(us, fv, st);
    for (std::size_t w = 0; w < who.size(); ++w) {
      const std::size_t i = who[w];
      if (st[2 * w] != "ok" || st[2 * w + 1] != "ok")
        return "hessian evaluation along " + hp.o.variables[i].label + ": " + (st[2 * w] != "ok" ? st[2 * w] : st[2 * w + 1]);
      const double rise = 0.5 * (fv[2 * w] + fv[2 * w + 1]) - f0;
      if (round == 4 || (rise >= target / 4 && rise <= target * 4)) {
        settled[i] = true;
        continue;
      }
      const double factor = rise > 0 ? std::clamp(std::sqrt(target / rise), 0.05, 20.0) : 10.0;
      h[i] = std::min(h[i] * factor, std::min(u0[i], 1 - u0[i]));
      if (!(h[i] > 0)) return hp.o.variables[i].label + " is at its bound: no central difference";
    }
  }
  return "";
}

// The Hessian in the scaled coordinates from ±h_i and (±h_i, ±h_j), i < j; an empty string, or
// which evaluation failed.
std::string hessian_at(HessianPoints& hp, const std::vector<double>& u0, const std::vector<double>& h, double f0,
                       Eigen::MatrixXd& H) {
  const std::size_t n = u0.size();
  struct Point { std::size_t i, j; int si, sj; };
  std::vector<Point> pts;
  for (std::size_t i = 0; i < n; ++i) for (const int si : {-1, +1}) pts.push_back({i, i, si, 0});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (const int si : {-1, +1}) for (const int sj : {-1, +1}) pts.push_back({i, j, si, sj});
  std::vector<std::vector<double>> us;
  for (const Point& pt : pts) {
    std::vector<double> u = u0;
    u[pt.i] += pt.si * h[pt.i];
    if (pt.sj != 0) u[pt.j] += pt.sj * h[pt.j];
    us.push_back(u);
  }
  std::vector<double> f;
  std::vector<std::string> status;
  hp.eval(us, f, status);
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (status[k] != "ok") return "hessian evaluation " + std::to_string(k + 1) + ": " + status[k];
  const auto N = static_cast<Eigen::Index>(n);
  H = Eigen::MatrixXd::Zero(N, N);
  std::size_t k = 0;
  for (Eigen::Index i = 0; i < N; ++i, k += 2) H(i, i) = (f[k] - 2 * f0 + f[k + 1]) / (h[i] * h[i]);
  for (Eigen::Index i = 0; i < N; ++i)
    for (Eigen::Index j = i + 1; j < N; ++j, k += 4)  // order: (−,−), (−,+), (+,−), (+,+)
      H(i, j) = H(j, i) = (f[k + 3] - f[k + 2] - f[k + 1] + f[k]) / (4 * h[i] * h[j]);
  return "";
}

// The Hessian of the objective at the optimum by central differences in the scaled coordinates,
// its covariance and the marginal standard deviations (fit.hpp, Uncertainty).
void run_uncertainty(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  Uncertainty& un = o.uncertainty;
  un.step = spec.hessian_step;
  const std::size_t n = o.variables.size();
  for (const std::size_t e : o.experiments) un.residuals += area_and_force_count(spec.experiments[e].scene.build(), spec.experiments[e], spec.noise, spec.force_score);
  const double f0 = o.objective;
  if (un.residuals <= static_cast<int>(n)) {
    un.failure = std::to_string(un.residuals) + " residuals for " + std::to_string(n) + " free variables";
    return;
  }
  un.reduced_chi2 = f0 / static_cast<double>(un.residuals - static_cast<int>(n));
  std::vector<double> u0, h, dxdu;
  if (un.failure = hessian_start(spec, o, u0, h, dxdu); !un.failure.empty()) return;
  HessianPoints hp{spec, pb, o};
  Eigen::MatrixXd H;
  un.failure = settle_steps(hp, u0, h, f0, un.reduced_chi2);
  if (un.failure.empty()) un.failure = hessian_at(hp, u0, h, f0, H);
  un.evaluations = hp.counter;
  if (!un.failure.empty()) return;
  const Eigen::LLT<Eigen::MatrixXd> llt(H);
  if (llt.info() != Eigen::Success) {
    std::string rows;
    for (Eigen::Index i = 0; i < H.rows(); ++i) {
      rows += i ? "; " : "";
      for (Eigen::Index j = 0; j < H.cols(); ++j) rows += (j ? " " : "") + g6(H(i, j));
    }
    un.failure = "the Hessian of the objective at the optimum is not positive definite (a flat or unidentifiable direction, "
                 "or the optimum is not a minimum on the step's scale): H = [" + rows + "] in the scaled coordinates";
    return;
  }
  const Eigen::MatrixXd inv = llt.solve(Eigen::MatrixXd::Identity(H.rows(), H.cols()));
  un.steps.resize(n);
  for (std::size_t i = 0; i < n; ++i) un.steps[i] = h[i] * std::abs(dxdu[i]) / std::abs(o.best[i]);
  un.sigma.resize(n);
  un.correlation.assign(n, std::vector<double>(n, 0.0));
  const auto I = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  for (std::size_t i = 0; i < n; ++i) un.sigma[i] = std::abs(dxdu[i]) * std::sqrt(2 * un.reduced_chi2 * inv(I(i), I(i)));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) un.correlation[i][j] = inv(I(i), I(j)) / std::sqrt(inv(I(i), I(i)) * inv(I(j), I(j)));
  un.computed = true;
  un.wall_s = seconds_since(t0);
  // The profiles' conditional intervals at the same rise s².
  for (ParameterProfile& pp : o.profiles)
    for (std::size_t v = 0; v < n; ++v)
      if (o.variables[v].parameter == pp.parameter && o.variables[v].experiment < 0)
        profile_interval(pp, f0, un.reduced_chi2, o.best[v]);
}

// The refits with each error-bar key shifted by -bar and +bar (in parallel, journaled).
void run_refits(const FitSpec& spec, const FitOptions& options, Optimization& o, Counts& counts, const StopFlag& stop,
                std::atomic<int>& ticked) {
  const auto t0 = Clock::now();
  std::vector<ErrorBarRefit> refits;
  for (const auto& eb : spec.error_bars)
    for (const int sign : {-1, +1}) refits.push_back({eb.key, eb.bar, sign, {}, Observables::nan, 0, "", ""});
  for_each_nested(refits.size(), [&](std::size_t i) {
    ErrorBarRefit& rf = refits[i];
    Problem q;
    q.spec = &spec;
    q.label = o.label;
    q.part = "refit " + rf.key + " " + (rf.sign < 0 ? "-1" : "+1");
    q.journal = options.journal;
    q.replay_only = options.replay_only;
    q.counts = &counts;
    q.stop = &stop;
    q.user_term = &options.user_term;
    q.on_evaluation = &options.on_evaluation;
    q.ticked = &ticked;
    q.exps = o.experiments;
    q.vars = o.variables;
    for (const std::size_t e : o.experiments) {
      const double nominal = scene_value(spec.experiments[e].scene.build(), rf.key);
      q.extra.push_back({{rf.key, nominal + rf.sign * rf.bar}});
    }
    // Start at the optimum with a smaller first step: the shift moves it little.
    OptimizeResult rr = optimize(std::move(q), o.best, spec.initial_step * 0.25, /*polish_only=*/true);
    rf.best = rr.best;
    rf.objective = rr.objective;
    rf.evaluations = static_cast<int>(rr.log.size());
    rf.stop_reason = rr.stop_reason;
    rf.failure = rr.failure;
  });
  o.refits = std::move(refits);
  o.refits_wall_s = seconds_since(t0);
}

// The line FitOptions::progress gets when an optimization is done, its profile and refits too:
// its own best objective and whether starts confirmed it first, then how it got there.
std::string done_line(const Problem& pb, const Optimization& o) {
  std::string line = o.label + ": ";
  if (o.best.empty() || !std::isfinite(o.objective)) line += "no successful evaluation";
  else line += "best J = " + g6(o.objective) + " at " + values_text(pb, o.best);
  line += ", converged: " + std::string(converged_name(o.converged)) + " (" + std::to_string(o.in_best_basin) + " of " +
          std::to_string(o.starts.size()) + " start(s) in the best basin), " + std::to_string(o.evaluations) +
          " evaluations, " + o.stop_reason + ", " + g6(o.wall_s) + " s";
  if (!o.failure.empty()) line += "; FAILED: " + o.failure;
  return line;
}

// The most evaluations one optimization with n free variables makes (fit_run_budget).
long long optimization_budget(const FitSpec& spec, const FitOptions& options, std::size_t n) {
  long long b = evaluation_budget(spec) + 1;  // the starts, the best point's re-run
  if (options.profile && spec.profile) {
    const ProfileSettings& ps = spec.profile_settings;
    b += static_cast<long long>(std::max<std::size_t>(ps.parameters.size(), 1)) * ps.points;
  }
  if (options.error_bars && spec.intervals && spec.objective == FitObjective::area_and_force) {
    const auto v = static_cast<long long>(n);
    b += 10 * v + 2 * v + 2 * v * (v - 1);  // settle_steps: <= 5 rounds of +-h_i; hessian_at
  }
  if (options.error_bars && !spec.error_bars.empty())  // a refit runs the local stage alone
    b += 2LL * static_cast<long long>(spec.error_bars.size()) *
         (spec.polish_algorithm.empty() ? spec.max_evaluations : spec.polish_max_evaluations);
  return b;
}

// Why an optimization whose every successful evaluation scored exactly 0 learnt nothing (empty
// otherwise): a flat objective is minimised by any point, so its "optimum" is only where it
// started (noise levels so large that every squared residual underflows, or a user term that
// ignores the run). A non-finite objective already fails its evaluation.
std::string degenerate_objective(const std::vector<Evaluation>& log) {
  int zero = 0;
  for (const Evaluation& ev : log) {
    if (ev.status != "ok") continue;
    if (ev.objective != 0) return "";
    ++zero;
  }
  if (zero == 0) return "";
  return "the objective is 0 at every one of its " + std::to_string(zero) +
         " evaluations: a degenerate objective (residuals that underflow, or that do not depend on the parameters)";
}

// One optimization (a task of the runner): optimize, then the best runs, the profile and the
// error-bar refits as asked.
void run_task(const FitSpec& spec, const FitOptions& options, Optimization& o, std::mutex& progress_mutex, Counts& counts,
              const StopFlag& stop) {
  std::atomic<int> ticked{0};
  Problem pb = fit_problem(spec, options, o, counts, stop);
  pb.ticked = &ticked;
  run_starts(spec, pb, o);
  if (o.failure.empty()) o.failure = degenerate_objective(o.log);
  const bool have_best = std::isfinite(o.objective);
  if (have_best) {
    Problem best = pb;  // the best evaluation's journal line is where its start journaled it
    best.part = o.starts[o.best_start].part;
    keep_best_runs(best, o);
  }
  if (have_best && o.ok() && options.profile && spec.profile) run_profile(spec, pb, o);
  if (have_best && o.ok() && options.error_bars && spec.intervals && spec.objective == FitObjective::area_and_force) {
    // Intervals describe a minimum: around a point no second start confirms they describe a slope.
    if (o.certified()) run_uncertainty(spec, pb, o);
    else o.uncertainty.failure = std::string("not certified (converged: ") + converged_name(o.converged) + "): " + o.convergence;
  }
  if (have_best && o.ok() && options.error_bars && !spec.error_bars.empty()) run_refits(spec, options, o, counts, stop, ticked);
  // What it did not use of its budget (early convergence, no profile around a failure, ...).
  const long long unused = optimization_budget(spec, options, o.variables.size()) - ticked.load();
  if (options.on_evaluation)
    options.on_evaluation(FitTick{&o.label, "done", Observables::nan, static_cast<int>(std::max(unused, 0LL))});
  if (options.progress) {
    const std::string line = done_line(pb, o);
    std::lock_guard<std::mutex> lock(progress_mutex);
    options.progress(line);
  }
}

}  // namespace

int evaluation_budget(const FitSpec& spec) {
  const bool polish = !spec.polish_algorithm.empty();
  const int local = polish ? spec.polish_max_evaluations : spec.max_evaluations;
  return spec.max_evaluations + (polish ? spec.polish_max_evaluations : 0) + (std::max(spec.starts, 1) - 1) * local;
}

std::string nlopt_result_name(int result) {
  const char* s = nlopt_result_to_string(static_cast<nlopt_result>(result));
  return s ? s : "UNKNOWN_RESULT_" + std::to_string(result);
}

double parameter_value(const FitParameter& p, double u) {
  u = std::clamp(u, 0.0, 1.0);
  double x = p.log_scale ? std::exp(std::log(p.lo) + u * std::log(p.hi / p.lo)) : p.lo + u * (p.hi - p.lo);
  if (u == 0.0) x = p.lo;  // exact ends, whatever the rounding of exp/log
  if (u == 1.0) x = p.hi;
  return std::clamp(x, p.lo, p.hi);
}

double parameter_coordinate(const FitParameter& p, double x) {
  x = std::clamp(x, p.lo, p.hi);
  const double u = p.log_scale ? std::log(x / p.lo) / std::log(p.hi / p.lo) : (x - p.lo) / (p.hi - p.lo);
  return std::clamp(u, 0.0, 1.0);
}

namespace {

// The optimizations run_fit runs (FitOptions::only), each with its variables and start.
std::vector<Optimization> optimizations(const FitSpec& spec, const FitOptions& options) {
  std::vector<Optimization> fits;
  auto make = [&](std::vector<std::size_t> exps, std::string label) {
    Optimization o;
    o.label = std::move(label);
    o.experiments = std::move(exps);
    for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
      const FitParameter& p = spec.parameters[j];
      if (p.per_experiment && o.experiments.size() > 1) {
        for (const std::size_t e : o.experiments) {
          o.variables.push_back({j, static_cast<std::ptrdiff_t>(e), p.key + "@" + spec.experiments[e].name});
          o.start.push_back(p.start);
        }
      } else {
        o.variables.push_back({j, -1, p.key});
        o.start.push_back(p.start);
      }
    }
    return o;
  };
  if (spec.separate) {
    for (std::size_t e = 0; e < spec.experiments.size(); ++e) fits.push_back(make({e}, spec.experiments[e].name));
  } else {
    std::vector<std::size_t> all(spec.experiments.size());
    for (std::size_t e = 0; e < all.size(); ++e) all[e] = e;
    fits.push_back(make(all, all.size() == 1 ? spec.experiments[0].name : std::string("joint")));
  }
  if (options.only.empty()) return fits;
  std::vector<Optimization> chosen;
  for (const std::size_t i : options.only) {
    if (i >= fits.size()) throw std::invalid_argument("run_fit: FitOptions::only names optimization " + std::to_string(i));
    chosen.push_back(std::move(fits[i]));
  }
  return chosen;
}

}  // namespace

long long fit_run_budget(const FitSpec& spec, const FitOptions& options) {
  long long total = 0;
  for (const Optimization& o : optimizations(spec, options)) total += optimization_budget(spec, options, o.variables.size());
  return total;
}

FitResult run_fit(const FitSpec& spec, const FitOptions& options) {
  if (spec.parameters.empty() || spec.experiments.empty())
    throw std::invalid_argument("run_fit: a fit needs at least one parameter and one experiment");
  const auto t0 = Clock::now();
  FitResult result;
  result.threads = std::max(1, options.threads);
  result.fits = optimizations(spec, options);

  std::mutex progress_mutex;
  Counts counts;
  const StopFlag stop(options.stop);
  // A RunInterrupted of one task leaves the others to see the stop themselves; the runner rethrows it here.
  ParallelRunner(result.threads).for_each(result.fits.size(), [&](std::size_t i) {
    run_task(spec, options, result.fits[i], progress_mutex, counts, stop);
  });
  result.replayed = counts.replayed;
  result.computed = counts.computed;
  result.wall_s = seconds_since(t0);
  for (const auto& o : result.fits) result.fit_wall_s += o.wall_s;
  return result;
}

}  // namespace asperity
