#pragma once
// The slider (docs/model.md §1, Eq. 1): a mass M pulled through a spring of stiffness k_L whose far
// end moves at v, damped at rate η, and held back by the total junction force F:
//     M Ẍ + M η Ẋ = k_L (v t − X) − F.
// This is where η enters the equations. Pure functions, SI units.

namespace asperity {

struct Slider {
  double mass_kg = 0;  // M
  double k_L = 0;      // N/m, loading spring
  double v = 0;        // m/s, driving velocity
  double eta = 0;      // 1/s, damping rate η

  // Spring tension Q = k_L (v t − X) [N]: the measured tangential force.
  double loading_force(double t_s, double X_m) const { return k_L * (v * t_s - X_m); }
  // Ẍ = (Q − F)/M − η Ẋ [m/s²] at spring tension Q, junction force F and velocity Ẋ. The
  // reference method passes the latest known velocity Ẋ(t) for γ(t+dt) (docs/model.md §3).
  double acceleration(double Q_n, double F_n, double V_mps) const { return (Q_n - F_n) / mass_kg - eta * V_mps; }
};

}  // namespace asperity
