#pragma once
// The paper's step-by-step scheme (Appendix 1, as ReferenceStepper) for interacting junctions
// (docs/model.md §8), with the coupled system solved at every step: the reference the fast
// interacting solver is checked against, for small N (a dense solve per step, O(N³)).
//
// One step at X(t+dt): (1) if |Ẋ(t)| < c_min v, every slipping junction repins, holding its
// force; (2) the other pinned junctions' forces are solved with the slipping and repinning ones
// held; (3) pinned junctions at or above their threshold slip (force ε f_s) and the rest are
// solved again at the same X, until none is over (an avalanche at fixed X; a junction changes
// state at most once per step, as in the paper's scan); (4) each repinned junction's anchor is
// set so that its equation holds with the forces now known (no force jump). With C_ij = 0 this
// is ReferenceStepper's step.
#include <algorithm>
#include <chrono>
#include <cstdint>

#include "solve/core/junction_state.hpp"
#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"
#include "solve/interacting/coupled_forces.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "solve/reference/reference_scheme.hpp"

namespace asperity {

class InteractingReferenceStepper {
 public:
  // Throws SolverError when the step is unstable for the linearised slider (as ReferenceStepper).
  explicit InteractingReferenceStepper(const Problem& problem);

  void start(RunObserver& out) { scheme_.emit_samples(out); }
  bool finished() const { return scheme_.finished(); }
  std::int64_t slips() const { return scheme_.slips(); }
  void advance(RunObserver& out);
  void stop_early() {}
  // The run's wall-time deadline (from stop.wall_time at construction; set_deadline only brings it
  // closer): a further avalanche round, or Newton iteration of a coupled solve, throws
  // WallTimeReached instead. Each is a dense O(N³) solve, and one step can hold many.
  void set_deadline(std::chrono::steady_clock::time_point deadline) { deadline_ = std::min(deadline_, deadline); }
  void clear_deadline() { deadline_ = std::chrono::steady_clock::time_point::max(); }
  void finish(RunInfo& info) const { scheme_.finish(info, max_ratio_); }

  const JunctionState& junctions() const { return J_; }

 private:
  const Problem& p_;
  ReferenceScheme scheme_;  // K0 (independent junctions) bounds the interacting stiffness: same check
  InteractionMatrix C_;
  CoupledForces forces_;
  JunctionState J_;
  double max_ratio_ = 0;
  std::chrono::steady_clock::time_point deadline_;
};

}  // namespace asperity
