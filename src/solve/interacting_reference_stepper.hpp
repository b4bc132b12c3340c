#pragma once
// The paper's step-by-step scheme (Appendix 1, as ReferenceStepper) for interacting junctions
// (MODEL.md §8), with the coupled system solved at every step: the reference the fast
// interacting solver is checked against, for small N (a dense solve per step, O(N³)).
//
// One step at X(t+dt): (1) if |Ẋ(t)| < c_min v, every slipping junction repins, holding its
// force; (2) the other pinned junctions' forces are solved with the slipping and repinning ones
// held; (3) pinned junctions at or above their threshold slip (force ε f_s) and the rest are
// solved again at the same X, until none is over (an avalanche at fixed X; a junction changes
// state at most once per step, as in the paper's scan); (4) each repinned junction's anchor is
// set so that its equation holds with the forces now known (no force jump). With C_ij = 0 this
// is ReferenceStepper's step.
#include <cstdint>

#include "solve/coupled_forces.hpp"
#include "solve/interaction_matrix.hpp"
#include "solve/junction_state.hpp"
#include "solve/observer.hpp"
#include "solve/problem.hpp"
#include "solve/run_info.hpp"

namespace asperity {

class InteractingReferenceStepper {
 public:
  // Throws SolverError when the step is unstable for the linearised slider (as ReferenceStepper).
  explicit InteractingReferenceStepper(const Problem& problem);

  void start(RunObserver& out);
  bool finished() const { return n_ >= n_end_; }
  std::int64_t slips() const { return stats_.slips; }
  void advance(RunObserver& out);
  void stop_early() {}
  void finish(RunInfo& info) const;

  const JunctionState& junctions() const { return J_; }

 private:
  void emit_samples(RunObserver& out) const;

  const Problem& p_;
  InteractionMatrix C_;
  CoupledForces forces_;
  JunctionState J_;
  std::int64_t n_ = 0, n_end_ = 0;
  double X_ = 0, V_ = 0, gamma_ = 0, A_sum_ = 0;
  std::int64_t n_slipping_ = 0, n_intact_ = 0;
  double prevQ_ = 0, prevA_ = 0, prevV_ = 0, prevt_ = 0;
  double max_ratio_ = 0;
  SolverStats stats_;
};

}  // namespace asperity
