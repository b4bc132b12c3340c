#pragma once
// The paper's Appendix 1 (`solver.method: reference`), exactly (docs/model.md §3): velocity Verlet
// at fixed dt = T0/C_t, the damping term of γ(t+dt) taken at Ẋ(t) (the latest known velocity),
// forces at X(t+dt), never-slipped junctions by bisection, t = n·dt.
#include <cstdint>

#include "solve/core/adaptive_team.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"
#include "solve/reference/reference_scheme.hpp"

namespace asperity {

class ReferenceStepper {
 public:
  // Throws SolverError when the step is unstable for the linearised slider.
  explicit ReferenceStepper(const Problem& problem);

  void start(RunObserver& out) { scheme_.emit_samples(out); }  // the samples due at t = 0
  bool finished() const { return scheme_.finished(); }
  std::int64_t slips() const { return scheme_.slips(); }
  void advance(RunObserver& out);  // one step of dt
  void stop_early() {}             // a resource limit: everything up to here is recorded
  void finish(RunInfo& info) const { scheme_.finish(info, max_ratio_); }

 private:
  const Problem& p_;
  ReferenceScheme scheme_;
  JunctionState J_;
  double max_ratio_ = 0;  // max f_i / (σ A_i)
  // The step's threads, chosen by measuring the steps (adaptive_team.hpp): on small populations a
  // team costs more than it saves (docs/performance.md, "Figures behind the code's choices").
  AdaptiveTeam team_;
};

}  // namespace asperity
