#pragma once
// Calibration with NLopt: minimises a FitSpec's objective over its free parameters (scaled to
// [0, 1], log or linear), runs each experiment's scene per evaluation, keeps every evaluation,
// then profiles the objective around the optimum and refits with each error-bar quantity at
// nominal ± bar. Plain data in and out; fit_writer.hpp writes the results directory.
//
// Threads: one nlopt::opt per optimization, owned by the task that runs it. In a joint fit the
// experiments of one evaluation run in parallel; with `separate` the per-experiment fits run in
// parallel (TBB, `threads` workers). Runs are single-threaded inside (OpenMP set to 1 thread in
// each task, so nothing oversubscribes the cores).
//
// Failures: an exception (SolverError, InputError), a NaN objective, or a run without a
// confirmed static friction peak (Observables::peak_found: its loading branch and Q_s are not
// the peak's; not with area_and_force, whose Q(t) term scores a run without a peak in the
// measured window as the poor fit it is) inside an evaluation ends that optimization with
// NLopt's forced stop; the reason
// is kept in Optimization::failure (status "failed", `asperity fit` exits 1) and the best
// evaluation so far is reported. An optimization whose every evaluation scored exactly 0 fails
// the same way (a degenerate objective: any point minimises it).
//
// Journal (FitOptions::journal, fit_journal.hpp): every evaluation is looked up first and
// journaled when computed, so a killed fit rerun with the same journal replays what it had done
// (NLopt's derivative-free algorithms ask for the same points in the same order) and ends with
// the uninterrupted result; array tasks run FitOptions::only, collect runs replay_only.
//
// Cancel (FitOptions::stop): every run polls it (RunMonitor) and stops within ~0.05 s; the
// evaluation it belonged to is dropped, not journaled, and run_fit throws RunInterrupted.
#include <atomic>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fit/convergence.hpp"
#include "fit/fit_spec.hpp"
#include "fit/objective.hpp"
#include "observe/observables.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

class FitJournal;  // fit/fit_journal.hpp
struct RunResult;  // observe/simulate.hpp

// What FitOptions::on_evaluation hears: one evaluation done (the runs of an optimization's
// experiments at one point), or (part "done") an optimization finished, profile and refits
// included, with `unused` of its share of fit_run_budget left: counting `unused` for each "done"
// and 1 for every other tick ends exactly at the budget.
struct FitTick {
  const std::string* label = nullptr;  // the optimization's (Optimization::label)
  const char* part = "";               // "fit" (its starts), "best" (re-run), "profile", "hessian", "refit"; "done"
  double objective = std::numeric_limits<double>::quiet_NaN();  // the evaluation's; NaN: failed
  int unused = 0;                                               // "done" only
  bool done() const { return std::string_view(part) == "done"; }
  // What this tick adds to a count that ends at fit_run_budget: one run, or a finished one's rest.
  int counted() const { return done() ? unused : 1; }
};

struct FitOptions {
  int threads = 2;         // TBB workers
  bool profile = true;     // and spec.profile
  bool error_bars = true;  // and spec.error_bars non-empty
  // Called (serialised) with one line after each finished optimization, its profile and refits
  // included: its label, best objective J and convergence; may be empty.
  std::function<void(const std::string&)> progress;
  // Called after every evaluation the fit makes, the optimizations', the best point's re-run,
  // the profiles', the Hessian's and the error-bar refits' (from worker threads: must be
  // thread-safe), and once per finished optimization with its unused budget; may be empty. For
  // progress lines against fit_run_budget.
  std::function<void(const FitTick&)> on_evaluation;
  // Every evaluation (optimizations, profile points, error-bar refits) goes through it: one
  // journaled at exactly the same values is replayed (no model run), a new one is appended as
  // soon as it finishes. May be null.
  FitJournal* journal = nullptr;
  // Collect (array tasks): every evaluation must come from the journal; the first that does not
  // ends run_fit with NotJournaled. The best runs are still re-run (for their curves).
  bool replay_only = false;
  // The optimizations to run, as indices into the list run_fit builds (one per experiment with
  // `separate`, in file order; else the one joint fit); empty: all. FitResult::fits then holds
  // only these.
  std::vector<std::size_t> only;
  // Cooperative cancel (the Python module's Ctrl-C; the command line is ended by the signal
  // itself): once *stop is true, no evaluation starts, the runs in flight stop, and run_fit throws
  // RunInterrupted (observe/run_monitor.hpp). Every evaluation that finished is in the journal,
  // none that did not: a rerun with it resumes. May be null.
  const std::atomic<bool>* stop = nullptr;
  // The term of one experiment's run for FitSpec::objective == FitObjective::user (required
  // then, unused otherwise): the caller's own objective (the Python module's callable), summed
  // over the experiments as the built-in terms are. Called from worker threads, concurrently: it
  // must be thread-safe. A NaN fails the evaluation as a NaN term does; RunInterrupted thrown
  // from it stops the fit as FitOptions::stop does (the caller keeps why); any other exception
  // fails the evaluation with its message.
  std::function<double(const FitExperiment&, const Scene&, const RunResult&)> user_term;
};

// run_fit with FitOptions::replay_only met an evaluation the journal does not hold.
struct NotJournaled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One coordinate of an optimization: a parameter, shared or for one experiment.
struct FreeVariable {
  std::size_t parameter = 0;       // index into FitSpec::parameters
  std::ptrdiff_t experiment = -1;  // index into FitSpec::experiments; -1: shared
  std::string label;               // "model.alpha_b" or "model.alpha_b@P0.98N"
};

struct Evaluation {
  int index = 0;               // 1-based, in call order
  std::vector<double> values;  // SI, one per free variable
  double objective = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> residuals;  // per experiment of the optimization
  std::string status = "ok";      // "ok" or why it failed
  double wall_s = 0;
};

// The best run of one experiment (at the fitted values).
struct ExperimentRun {
  JointTerms terms;            // area_and_force: the term by part (objective.hpp)
  std::vector<Sample> series;  // area_and_force: the run's Q(t) samples
  std::optional<MeasuredForce> force;
  std::size_t experiment = 0;  // index into FitSpec::experiments
  double residual = std::numeric_limits<double>::quiet_NaN();
  Observables obs;
  std::vector<Sample> loading;  // loading branch
  double mass_kg = 0;
  bool stand_in = false;  // the experiment's description says STAND-IN
  std::optional<MeasuredCurve> measured;
};

struct ProfilePoint {
  double factor = 1;  // x = x* · factor
  double value = 0;   // SI
  double objective = std::numeric_limits<double>::quiet_NaN();
  std::string status = "ok";
};

// The objective along one parameter, the others at the optimum (a slice through it), and where
// it rises by s² (Uncertainty::reduced_chi2) on each side: the conditional interval (narrower
// than the marginal one when parameters are correlated). NaN where the span does not reach it.
struct ParameterProfile {
  std::size_t parameter = 0;  // index into FitSpec::parameters
  std::vector<ProfilePoint> points;
  double lo = std::numeric_limits<double>::quiet_NaN(), hi = std::numeric_limits<double>::quiet_NaN();
  // sqrt(s² / c) for the least-squares parabola J ≈ a + b d + c d² through the profile's points
  // (d = value − optimum): a conditional standard deviation over the whole span, robust to
  // roughness and jumps of J at scales below the points' spacing (where the Hessian is not);
  // NaN when c ≤ 0 or fewer than 3 points.
  double parabola_sigma = std::numeric_limits<double>::quiet_NaN();
};

// Statistical uncertainty of an area_and_force fit (a chi-square J): the Hessian H of J at the
// optimum in the optimizer's scaled coordinates by central differences (journaled evaluations,
// part "hessian": each parameter's step is first rescaled from hessian_step until its own rise
// is 1–16 s², then 2n + 2n(n−1) points), the covariance 2 s² H⁻¹ mapped to SI, with s² = J_min/(N − n)
// the reduced chi-square (N residuals, n free variables): 1 when the noise levels are right and
// the model fits; larger when it does not, and the intervals widen accordingly.
struct Uncertainty {
  bool computed = false;
  std::string failure;  // why not (at a bound, H not positive definite, ...)
  int residuals = 0;    // N
  double reduced_chi2 = std::numeric_limits<double>::quiet_NaN();
  double step = 0;            // the initial relative step of each parameter
  std::vector<double> steps;  // the steps used, relative to each value
  std::vector<double> sigma;  // SI, per free variable (marginal standard deviation)
  std::vector<std::vector<double>> correlation;
  int evaluations = 0;
  double wall_s = 0;
};

// Where one local search ended: a start, an error-bar refit, a bootstrap refit.
struct LocalOptimum {
  std::vector<double> best;  // SI, per free variable (NaN when it failed)
  double objective = std::numeric_limits<double>::quiet_NaN();
  int evaluations = 0;
  std::string stop_reason;
  std::string failure;
};

// One synthetic data set of the parametric bootstrap (FitSpec::bootstrap_draws): its refit.
using BootstrapDraw = LocalOptimum;

// The spread of the bootstrap refits' optima: per free variable their mean and standard
// deviation (n − 1), over the draws whose refit succeeded.
struct Bootstrap {
  std::vector<BootstrapDraw> draws;
  int succeeded = 0;
  std::vector<double> mean, sigma;  // SI, per free variable (empty when fewer than 2 succeeded)
  std::string failure;              // why no σ (the model's curves, too few refits)
  int evaluations = 0;
  double wall_s = 0;
};

struct ErrorBarRefit : LocalOptimum {
  std::string key;
  double bar = 0;
  int sign = 0;  // −1: nominal − bar, +1: nominal + bar
};

// One start of an optimization (FitSpec::starts): the first runs the algorithm (then the polish)
// from the file's start, journaled as part "fit"; start K ≥ 2 runs the local stage from a Sobol
// point, part "fit start K".
struct StartRun : LocalOptimum {  // best: NaN before any successful evaluation
  std::string part;               // its journal part
  std::vector<double> from;       // SI
  bool in_best_basin = false;
};

struct Optimization {
  std::string label;                     // experiment name (separate) or "joint"
  std::vector<std::size_t> experiments;  // indices into FitSpec::experiments
  std::vector<FreeVariable> variables;
  std::vector<double> start;  // SI
  std::vector<double> best;   // SI (NaN before any successful evaluation)
  double objective = std::numeric_limits<double>::quiet_NaN();
  std::string stop_reason;  // NLopt result, e.g. XTOL_REACHED, FORCED_STOP
  std::string failure;      // empty when the fit ended normally
  int evaluations = 0;
  double wall_s = 0;            // the optimization itself
  std::vector<Evaluation> log;  // every start's evaluations, start after start
  std::vector<StartRun> starts;
  std::size_t best_start = 0;  // index into starts of the best one
  Converged converged = Converged::unverified;
  std::string convergence;  // why (ConvergenceVerdict::reason)
  int in_best_basin = 0;    // starts in the best basin (the best included)
  double spread = 0;        // their largest scaled distance from the best
  bool certified() const { return converged == Converged::yes; }
  std::vector<ExperimentRun> best_runs;  // empty when no evaluation succeeded
  std::vector<ProfilePoint> profile;     // the first profiled parameter's (= profiles[0].points)
  std::size_t profile_parameter = 0;
  std::vector<ParameterProfile> profiles;  // every profiled parameter
  Uncertainty uncertainty;
  Bootstrap bootstrap;  // FitSpec::bootstrap_draws > 0 at a certified optimum
  std::vector<ErrorBarRefit> refits;
  double profile_wall_s = 0, refits_wall_s = 0;
  bool ok() const { return failure.empty(); }
};

struct FitResult {
  std::vector<Optimization> fits;  // one (joint) or one per experiment (separate)
  double wall_s = 0;               // everything
  double fit_wall_s = 0;           // sum of the optimizations' wall times (no profile, refits)
  int threads = 1;
  int replayed = 0;  // evaluations answered from FitOptions::journal
  int computed = 0;  // evaluations that ran the model (profiles and refits included)
};

// NLopt's name of a result code (e.g. "XTOL_REACHED").
std::string nlopt_result_name(int result);

// The most evaluations the optimizations of one fit can take (the global stage once, then each
// start's local stage).
int evaluation_budget(const FitSpec& spec);

// The most evaluations run_fit makes with these options: per optimization its starts
// (evaluation_budget), the best point's re-run, the profiles, the Hessian and the error-bar
// refits, over the optimizations FitOptions::only names: the progress line's total.
long long fit_run_budget(const FitSpec& spec, const FitOptions& options);

// Minimises; never throws for a failing evaluation (see Optimization::failure). RunInterrupted
// when FitOptions::stop cut it short.
FitResult run_fit(const FitSpec& spec, const FitOptions& options = {});

// The physical value of scaled coordinate u ∈ [0, 1] (clamped), exactly within [lo, hi].
double parameter_value(const FitParameter& p, double u);
double parameter_coordinate(const FitParameter& p, double x);  // inverse

}  // namespace asperity
