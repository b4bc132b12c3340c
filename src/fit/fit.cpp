#include "fit/fit.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>

#include "batch/parallel_runner.hpp"
#include "batch/stop_flag.hpp"
#include "fit/fit_journal.hpp"
#include "fit/fit_problem.hpp"
#include "fit/fit_uncertainty.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "observe/run_monitor.hpp"

namespace asperity::fit_detail {

namespace {

// NLopt's objective: the problem (`data`) at the scaled point u, journaled. A failed evaluation,
// the stop and a replay's missing evaluation end the stage with NLopt's forced stop.
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
  tick(pb,
       pb.part.rfind("refit", 0) == 0       ? "refit"
       : pb.part.rfind("bootstrap", 0) == 0 ? "bootstrap"
                                            : "fit",
       ev.objective);
  if (ev.status != "ok") {
    // Every digit: a solver failure may hang on the exact point (the 6-digit rounding ran through).
    pb.failure = "evaluation " + std::to_string(ev.index) + " (" + values_text(pb, x, true) + "): " + ev.status;
    throw nlopt::forced_stop();  // caught by NLopt's C++ wrapper, rethrown by optimize()
  }
  return ev.objective;
}

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

}  // namespace

// Runs the optimization's problem (Problem::part set) from `start`: the algorithm, then the
// polish stage from its best point when the spec has one (fit_problem.hpp).
LocalOptimum local_optimum(const OptimizeResult& r) {
  return {r.best, r.objective, static_cast<int>(r.log.size()), r.stop_reason, r.failure};
}

OptimizeResult optimize(Problem pb, const std::vector<double>& start, double initial_step, bool polish_only) {
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

namespace {

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
  for (std::size_t i = 0; i < n; ++i)
    u0[i] = parameter_coordinate(spec.parameters[o.variables[i].parameter], o.start[i]);
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
    StartRun sr{local_optimum(r), start_part(k), from[k], false};
    if (o.failure.empty() && !r.failure.empty())
      o.failure = (k == 0 ? "" : "start " + std::to_string(k + 1) + ": ") + r.failure;
    StartEnd e{std::vector<double>(r.best.size()), r.objective};
    for (std::size_t i = 0; i < r.best.size(); ++i)
      e.u[i] = parameter_coordinate(spec.parameters[o.variables[i].parameter], r.best[i]);
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
    throw io::InputError(at->first, at->second, "objective", msg);
  }
}

// The line FitOptions::progress gets when an optimization is done, its profile and refits too:
// its own best objective and whether starts confirmed it first, then how it got there.
std::string done_line(const Problem& pb, const Optimization& o) {
  std::string line = o.label + ": ";
  if (o.best.empty() || !std::isfinite(o.objective))
    line += "no successful evaluation";
  else
    line += "best J = " + io::format_significant(o.objective) + " at " + values_text(pb, o.best);
  line += ", converged: " + std::string(converged_name(o.converged)) + " (" + std::to_string(o.in_best_basin) + " of " +
          std::to_string(o.starts.size()) + " start(s) in the best basin), " + std::to_string(o.evaluations) +
          " evaluations, " + o.stop_reason + ", " + io::format_significant(o.wall_s) + " s";
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
  if (options.error_bars && spec.intervals && spec.objective == FitObjective::area_and_force)
    b += static_cast<long long>(spec.bootstrap_draws) *  // a bootstrap refit runs the local stage alone
         (spec.polish_algorithm.empty() ? spec.max_evaluations : spec.polish_max_evaluations);
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
void run_task(const FitSpec& spec, const FitOptions& options, Optimization& o, std::mutex& progress_mutex,
              Counts& counts, const StopFlag& stop) {
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
    if (o.certified()) {
      run_uncertainty(spec, pb, o);
      if (spec.bootstrap_draws > 0) run_bootstrap(spec, pb, o);
    } else
      o.uncertainty.failure =
          std::string("not certified (converged: ") + converged_name(o.converged) + "): " + o.convergence;
  }
  if (have_best && o.ok() && options.error_bars && !spec.error_bars.empty())
    run_refits(spec, options, o, counts, stop, ticked);
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
    if (i >= fits.size())
      throw std::invalid_argument("run_fit: FitOptions::only names optimization " + std::to_string(i));
    chosen.push_back(std::move(fits[i]));
  }
  return chosen;
}

}  // namespace

}  // namespace asperity::fit_detail

namespace asperity {

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

long long fit_run_budget(const FitSpec& spec, const FitOptions& options) {
  long long total = 0;
  for (const Optimization& o : fit_detail::optimizations(spec, options))
    total += fit_detail::optimization_budget(spec, options, o.variables.size());
  return total;
}

FitResult run_fit(const FitSpec& spec, const FitOptions& options) {
  if (spec.parameters.empty() || spec.experiments.empty())
    throw std::invalid_argument("run_fit: a fit needs at least one parameter and one experiment");
  const auto t0 = fit_detail::Clock::now();
  FitResult result;
  result.threads = std::max(1, options.threads);
  result.fits = fit_detail::optimizations(spec, options);

  std::mutex progress_mutex;
  fit_detail::Counts counts;
  const StopFlag stop(options.stop);
  // A RunInterrupted of one task leaves the others to see the stop themselves; the runner rethrows it here.
  ParallelRunner(result.threads).for_each(result.fits.size(), [&](std::size_t i) {
    fit_detail::run_task(spec, options, result.fits[i], progress_mutex, counts, stop);
  });
  result.replayed = counts.replayed;
  result.computed = counts.computed;
  result.wall_s = fit_detail::seconds_since(t0);
  for (const auto& o : result.fits) result.fit_wall_s += o.wall_s;
  return result;
}

}  // namespace asperity
