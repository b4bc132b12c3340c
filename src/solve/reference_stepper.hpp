#pragma once
// The paper's Appendix 1 (`solver.method: reference`), exactly (MODEL.md §3): velocity Verlet
// at fixed dt = T0/C_t, the damping term of γ(t+dt) taken at Ẋ(t) (the latest known velocity),
// forces at X(t+dt), never-slipped junctions by bisection, t = n·dt.
#include <cstdint>

#include "solve/junction_state.hpp"
#include "solve/observer.hpp"
#include "solve/problem.hpp"
#include "solve/run_info.hpp"

namespace asperity {

class ReferenceStepper {
 public:
  // Throws SolverError when the step is unstable for the linearised slider.
  explicit ReferenceStepper(const Problem& problem);

  void start(RunObserver& out);    // the samples due at t = 0
  bool finished() const { return n_ >= n_end_; }
  std::int64_t slips() const { return stats_.slips; }
  void advance(RunObserver& out);  // one step of dt
  void stop_early() {}             // a resource limit: everything up to here is recorded
  void finish(RunInfo& info) const;

 private:
  void emit_samples(RunObserver& out) const;

  const Problem& p_;
  JunctionState J_;
  std::int64_t n_ = 0, n_end_ = 0;  // steps done, steps to stop.time
  double X_ = 0, V_ = 0, gamma_ = 0, A_sum_ = 0;
  std::int64_t n_slipping_ = 0, n_intact_ = 0;
  double prevQ_ = 0, prevA_ = 0, prevV_ = 0, prevt_ = 0;  // the previous step, for extrema of Q
  double max_ratio_ = 0;                                  // max f_i / (σ A_i)
  SolverStats stats_;
};

// Spectral radius of the reference's one-step map for the linearised slider (stiffness
// k_L + K0, damping η); > 1 means the explicit step is unstable.
double reference_spectral_radius(double omega_dt, double eta_dt);

}  // namespace asperity
