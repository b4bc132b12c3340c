#include "fit/fit.hpp"

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
    } else {
      out.residual = experiment_residual(spec.objective, scene, r.obs, r.recorder.loading_branch(), fe.target);
    }
    if (std::isnan(out.residual) && spec.objective == FitObjective::user) {
      out.error = "objective term of " + fe.name + " is NaN (the user objective returned nan)";
    } else if (std::isnan(out.residual)) {
      out.error = "objective term of " + fe.name + " is NaN (model alpha = " + g6(r.obs.alpha) +
                  ", measured alpha = " + g6(r.obs.alpha_measured) + ", Q_s = " + g6(r.obs.Q_s) +
                  ", loading-branch points = " + std::to_string(r.recorder.loading_branch().size()) + ")";
    } else if (!r.obs.peak_found) {
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
  const std::function<void(double)>* on_evaluation = nullptr;  // FitOptions::on_evaluation
  FitJournal* journal = nullptr;                               // FitOptions::journal
  bool replay_only = false;                                    // FitOptions::replay_only
  Counts* counts = nullptr;
  std::string not_journaled;  // replay_only: the evaluation the journal lacked
  const StopFlag* stop = nullptr;     // FitOptions::stop, polled by every run
  const UserTerm* user_term = nullptr;  // FitOptions::user_term
  bool interrupted = false;           // the stop ended the optimization
};

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

std::string values_text(const Problem& pb, const std::vector<double>& x) {
  std::string s;
  for (std::size_t i = 0; i < x.size(); ++i) s += (i ? ", " : "") + pb.vars[i].label + " = " + g6(x[i]);
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
  if (pb.on_evaluation && *pb.on_evaluation) (*pb.on_evaluation)(ev.objective);
  if (ev.status != "ok") {
    pb.failure = "evaluation " + std::to_string(ev.index) + " (" + values_text(pb, x) + "): " + ev.status;
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

// Runs the optimization's problem (Problem::part set) from `start`. NotJournaled when replay_only
// and an evaluation was not journaled.
OptimizeResult optimize(Problem pb, const std::vector<double>& start, double initial_step) {
  const FitSpec& spec = *pb.spec;
  const auto n = static_cast<unsigned>(pb.vars.size());
  OptimizeResult out;
  const auto t0 = Clock::now();
  nlopt::opt opt(static_cast<nlopt::algorithm>(nlopt_algorithm_from_string(spec.algorithm.c_str())), n);
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  std::vector<double> xtol(n), u(n), step(n, initial_step);
  for (unsigned i = 0; i < n; ++i) {
    const FitParameter& p = spec.parameters[pb.vars[i].parameter];
    u[i] = parameter_coordinate(p, start[i]);
    // xtol_rel on x → absolute on the scaled coordinate: Δu = Δx/x / ln(hi/lo) (log scale),
    // Δu = xtol_rel·|x_ref| / (hi − lo) (linear, x_ref = start, or the larger bound if 0).
    const double ref = start[i] != 0 ? std::abs(start[i]) : std::max(std::abs(p.lo), std::abs(p.hi));
    xtol[i] = p.log_scale ? spec.xtol_rel / std::log(p.hi / p.lo) : spec.xtol_rel * ref / (p.hi - p.lo);
  }
  opt.set_xtol_abs(xtol);
  if (spec.ftol_rel > 0) opt.set_ftol_rel(spec.ftol_rel);
  if (spec.ftol_abs > 0) opt.set_ftol_abs(spec.ftol_abs);
  opt.set_maxeval(spec.max_evaluations);
  opt.set_initial_step(step);
  opt.set_min_objective(nlopt_objective, &pb);
  double f = 0;
  try {
    out.stop_reason = nlopt_result_name(opt.optimize(u, f));
  } catch (const nlopt::forced_stop&) {
    out.stop_reason = "FORCED_STOP";
    out.failure = pb.failure.empty() ? "NLopt forced stop" : pb.failure;
  } catch (const nlopt::roundoff_limited&) {
    out.stop_reason = "ROUNDOFF_LIMITED";  // best point so far is still the answer
  } catch (const std::exception& e) {
    out.stop_reason = "FAILURE";
    out.failure = std::string("NLopt: ") + e.what();
  }
  out.wall_s = seconds_since(t0);
  if (pb.interrupted) throw RunInterrupted("fit interrupted in " + pb.part + " " + pb.label);
  if (!pb.not_journaled.empty()) throw NotJournaled(pb.not_journaled);
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

// The best runs, kept for the report (deterministic: same objective as journaled).
void keep_best_runs(const Problem& pb, Optimization& o) {
  std::vector<ExperimentEval> runs;
  const Evaluation ev = evaluate(pb, o.best, &runs);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    ExperimentRun er;
    er.experiment = o.experiments[k];
    er.residual = runs[k].residual;
    er.obs = runs[k].obs;
    er.loading = std::move(runs[k].loading);
    er.mass_kg = runs[k].mass_kg;
    er.stand_in = runs[k].stand_in;
    er.measured = std::move(runs[k].measured);
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

// The objective along the profiled parameter around the optimum (in parallel, journaled).
void run_profile(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  const ProfileSettings& ps = spec.profile_settings;
  const FitParameter& p = spec.parameters[ps.parameter];
  o.profile_parameter = ps.parameter;
  std::vector<ProfilePoint> pts(static_cast<std::size_t>(ps.points));
  for_each_nested(pts.size(), [&](std::size_t i) {
    ProfilePoint& pt = pts[i];
    pt.factor = 1.0 + ps.span * (2.0 * static_cast<double>(i) / static_cast<double>(pts.size() - 1) - 1.0);
    std::vector<double> x = o.best;
    bool inside = true;
    for (std::size_t j = 0; j < x.size(); ++j)
      if (o.variables[j].parameter == ps.parameter) {
        x[j] = o.best[j] * pt.factor;
        pt.value = x[j];
        inside = inside && x[j] >= p.lo && x[j] <= p.hi;
      }
    if (!inside) {
      pt.status = "outside the bounds";
      return;
    }
    Problem q = pb;
    q.part = "profile";
    const std::optional<Evaluation> ev = evaluate_journaled(q, static_cast<int>(i) + 1, x);
    if (!ev) throw NotJournaled(not_journaled_text(q, static_cast<int>(i) + 1, x));
    pt.objective = ev->objective;
    pt.status = ev->status;
  });
  o.profile = std::move(pts);
  o.profile_wall_s = seconds_since(t0);
}

// The refits with each error-bar key shifted by -bar and +bar (in parallel, journaled).
void run_refits(const FitSpec& spec, const FitOptions& options, Optimization& o, Counts& counts, const StopFlag& stop) {
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
    q.exps = o.experiments;
    q.vars = o.variables;
    for (const std::size_t e : o.experiments) {
      const double nominal = scene_value(spec.experiments[e].scene.build(), rf.key);
      q.extra.push_back({{rf.key, nominal + rf.sign * rf.bar}});
    }
    // Start at the optimum with a smaller first step: the shift moves it little.
    OptimizeResult rr = optimize(std::move(q), o.best, spec.initial_step * 0.25);
    rf.best = rr.best;
    rf.objective = rr.objective;
    rf.evaluations = static_cast<int>(rr.log.size());
    rf.stop_reason = rr.stop_reason;
    rf.failure = rr.failure;
  });
  o.refits = std::move(refits);
  o.refits_wall_s = seconds_since(t0);
}

// The line FitOptions::progress gets when an optimization is done.
std::string done_line(const Problem& pb, const Optimization& o) {
  std::string line = o.label + ": ";
  if (o.best.empty() || !std::isfinite(o.objective)) line += "no successful evaluation";
  else line += values_text(pb, o.best) + ", objective " + g6(o.objective);
  line += ", " + std::to_string(o.evaluations) + " evaluations, " + o.stop_reason + ", " + g6(o.wall_s) + " s";
  if (!o.failure.empty()) line += "; FAILED: " + o.failure;
  return line;
}

// One optimization (a task of the runner): optimize, then the best runs, the profile and the
// error-bar refits as asked.
void run_task(const FitSpec& spec, const FitOptions& options, Optimization& o, std::mutex& progress_mutex, Counts& counts,
              const StopFlag& stop) {
  const Problem pb = fit_problem(spec, options, o, counts, stop);
  OptimizeResult r = optimize(pb, o.start, spec.initial_step);
  o.best = r.best;
  o.objective = r.objective;
  o.stop_reason = r.stop_reason;
  o.failure = r.failure;
  o.evaluations = static_cast<int>(r.log.size());
  o.wall_s = r.wall_s;
  o.log = std::move(r.log);
  const bool have_best = std::isfinite(o.objective);
  if (have_best) keep_best_runs(pb, o);
  if (have_best && o.ok() && options.profile && spec.profile) run_profile(spec, pb, o);
  if (have_best && o.ok() && options.error_bars && !spec.error_bars.empty()) run_refits(spec, options, o, counts, stop);
  if (options.progress) {
    const std::string line = done_line(pb, o);
    std::lock_guard<std::mutex> lock(progress_mutex);
    options.progress(line);
  }
}

}  // namespace

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

FitResult run_fit(const FitSpec& spec, const FitOptions& options) {
  if (spec.parameters.empty() || spec.experiments.empty())
    throw std::invalid_argument("run_fit: a fit needs at least one parameter and one experiment");
  const auto t0 = Clock::now();
  FitResult result;
  result.threads = std::max(1, options.threads);

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
    for (std::size_t e = 0; e < spec.experiments.size(); ++e) result.fits.push_back(make({e}, spec.experiments[e].name));
  } else {
    std::vector<std::size_t> all(spec.experiments.size());
    for (std::size_t e = 0; e < all.size(); ++e) all[e] = e;
    result.fits.push_back(make(all, all.size() == 1 ? spec.experiments[0].name : std::string("joint")));
  }

  if (!options.only.empty()) {
    std::vector<Optimization> chosen;
    for (const std::size_t i : options.only) {
      if (i >= result.fits.size()) throw std::invalid_argument("run_fit: FitOptions::only names optimization " + std::to_string(i));
      chosen.push_back(std::move(result.fits[i]));
    }
    result.fits = std::move(chosen);
  }

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
