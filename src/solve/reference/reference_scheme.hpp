#pragma once
// The paper's step-by-step scheme (Appendix 1) apart from the junctions: the fixed step
// dt = T0/C_t and its stability check, velocity Verlet for the slider with the damping of
// γ(t+dt) taken at Ẋ(t), the samples at t = n·dt, the extrema of Q, the statistics. The
// reference steppers (independent, interacting) differ only in how they find the junction
// forces at X(t+dt); each step: next_X(), then the junctions, then complete().
#include <cmath>
#include <cstdint>

#include "solve/core/junction_state.hpp"
#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"

namespace asperity {

// Spectral radius of the reference's one-step map for the linearised slider (stiffness
// k_L + K0, damping η); > 1 means the explicit step is unstable.
double reference_spectral_radius(double omega_dt, double eta_dt);

// What the junctions give the slider after a step: Σ f_i, Σ A_i and the counts.
struct JunctionTotals {
  double F = 0, A = 0;
  std::int64_t n_slipping = 0, n_intact = 0;
};

// Σ over the junctions in index order (the result does not depend on a thread count); raises
// *max_ratio to the largest f_i/(σ A_i).
JunctionTotals junction_totals(const JunctionState& J, double sigma, double* max_ratio);

class ReferenceScheme {
 public:
  // Throws SolverError when the step is unstable for the linearised slider.
  explicit ReferenceScheme(const Problem& problem);

  bool finished() const { return n_ >= n_end_; }
  double next_t() const { return static_cast<double>(n_ + 1) * p_.dt; }
  double next_X() const { return X_ + p_.dt * V_ + 0.5 * p_.dt * p_.dt * gamma_; }
  bool slow() const { return std::abs(V_) < p_.repin_speed(); }  // |Ẋ(t)|, the latest known velocity
  void emit_samples(RunObserver& out) const;
  // Ends the step at X = next_X() with the junctions' totals there: the slider's velocity and
  // acceleration, the statistics, the reports (population change, extrema of Q, samples).
  void complete(RunObserver& out, const JunctionTotals& j, std::int64_t slips, bool any_repin,
                std::int64_t force_evals);
  void finish(RunInfo& info, double max_ratio) const;
  std::int64_t slips() const { return stats_.slips; }

 private:
  const Problem& p_;
  std::int64_t n_ = 0, n_end_ = 0;
  double X_ = 0, V_ = 0, gamma_ = 0, A_sum_ = 0;
  std::int64_t n_slipping_ = 0, n_intact_ = 0;
  double prevQ_ = 0, prevA_ = 0, prevV_ = 0, prevt_ = 0;  // the previous step, for extrema of Q
  SolverStats stats_;
};

}  // namespace asperity
