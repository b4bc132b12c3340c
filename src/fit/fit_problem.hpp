#pragma once
// One optimization's problem, shared by the optimizer's driving (fit.cpp) and the uncertainty
// around its optimum (fit_uncertainty.cpp): its experiments, free variables, fixed shifts and
// journal part; the objective at a point (every experiment run, journaled); and its NLopt run
// from a start. Internal to fit/.
#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fit/fit.hpp"
#include "io/numbers.hpp"

namespace asperity {
class StopFlag;  // batch/stop_flag.hpp
struct Scene;    // scene/scene.hpp
}  // namespace asperity

namespace asperity::fit_detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Six significant digits: the numbers of the fit's messages and progress lines.

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

// FitOptions::user_term.
using UserTerm = std::function<double(const FitExperiment&, const Scene&, const RunResult&)>;

// Evaluations answered from the journal and computed, over the whole fit.
struct Counts {
  std::atomic<int> replayed{0}, computed{0};
};

// One optimization's problem (a start, the profile, a refit), as NLopt's objective sees it.
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
  FitJournal* journal = nullptr;       // FitOptions::journal
  bool replay_only = false;            // FitOptions::replay_only
  Counts* counts = nullptr;
  std::string not_journaled;            // replay_only: the evaluation the journal lacked
  const StopFlag* stop = nullptr;       // FitOptions::stop, polled by every run
  const UserTerm* user_term = nullptr;  // FitOptions::user_term
  bool interrupted = false;             // the stop ended the optimization
};

// Tells FitOptions::on_evaluation that an evaluation of the optimization is done.
void tick(const Problem& pb, const char* part, double objective);

// All experiments of the problem at x (in parallel); the objective is their sum in order.
// `runs`: where each experiment's run is kept for the report (null: not kept).
Evaluation evaluate(const Problem& pb, const std::vector<double>& x, std::vector<ExperimentEval>* runs = nullptr);

// every_digit: the shortest text that reads back exactly (a failure may hang on the exact point).
std::string values_text(const Problem& pb, const std::vector<double>& x, bool every_digit = false);

// evaluate() through the journal: an evaluation of this (part, optimization) journaled at exactly
// x is returned as it was (no model run; also a point NLopt asks for twice in one run, which the
// deterministic model would give again anyway); a new one is appended as soon as it finishes.
// Without the journal entry in replay_only mode: nullopt (the caller stops).
std::optional<Evaluation> evaluate_journaled(const Problem& pb, int index, const std::vector<double>& x);

// The message of NotJournaled for that evaluation.
std::string not_journaled_text(const Problem& pb, int index, const std::vector<double>& x);

struct OptimizeResult {
  std::vector<double> best;
  double objective = Observables::nan;
  std::string stop_reason, failure;
  std::vector<Evaluation> log;
  double wall_s = 0;
};

// Runs the optimization's problem (Problem::part set) from `start`: the algorithm, then the
// polish stage from its best point when the spec has one (`polish_only`: the polish alone, or
// the algorithm when there is none). NotJournaled when replay_only and an evaluation was not
// journaled. (fit.cpp, with NLopt's objective and stages.)
OptimizeResult optimize(Problem pb, const std::vector<double>& start, double initial_step, bool polish_only = false);

// Where the search of `r` ended, as Optimization records it.
LocalOptimum local_optimum(const OptimizeResult& r);

}  // namespace asperity::fit_detail
