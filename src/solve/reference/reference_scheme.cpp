#include "solve/reference/reference_scheme.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>

namespace asperity {

double reference_spectral_radius(double omega_dt, double eta_dt) {
  // Variables (X, h V, h² γ) for X'' = −ω² X − η Ẋ; the same map as the step below.
  const double a = omega_dt * omega_dt, b = eta_dt;
  // Eigen's eigensolver does not return on a matrix with inf or NaN (an absurd dt).
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix3d m;
  // x1 = x + u + g/2;  g1 = −a x1 − b u;  u1 = u + (g + g1)/2
  m << 1, 1, 0.5,                                       // x1
      -0.5 * a, 1 - 0.5 * a - 0.5 * b, 0.5 - 0.25 * a,  // u1
      -a, -a - b, -0.5 * a;                             // g1
  return m.eigenvalues().cwiseAbs().maxCoeff();
}

JunctionTotals junction_totals(const JunctionState& J, double sigma, double* max_ratio) {
  JunctionTotals t;
  for (std::size_t i = 0; i < J.size(); ++i) {
    t.F += J.force[i];
    t.A += J.area[i];
    t.n_slipping += !J.pinned[i];
    t.n_intact += J.intact[i];
    const double r = J.force[i] / (sigma * J.area[i]);
    if (r > *max_ratio) *max_ratio = r;
  }
  return t;
}

ReferenceScheme::ReferenceScheme(const Problem& problem) : p_(problem) {
  const double dt = p_.dt;
  const double rho =
      reference_spectral_radius(std::sqrt((p_.K0 + p_.slider.k_L) / p_.slider.mass_kg) * dt, p_.slider.eta * dt);
  if (rho > 1.0 + 1e-12) {
    char msg[200];
    std::snprintf(
        msg, sizeof msg,
        "reference step unstable: spectral radius %.6g > 1 at dt = %.6g s (raise solver.Ct or lower model.eta)", rho,
        dt);
    throw SolverError(msg);
  }
  n_end_ = static_cast<std::int64_t>(std::ceil(p_.t_stop / dt - 1e-9));
  A_sum_ = p_.A0_sum;
  prevA_ = p_.A0_sum;
  n_intact_ = static_cast<std::int64_t>(p_.size());
}

void ReferenceScheme::emit_samples(RunObserver& out) const {
  const double t = static_cast<double>(n_) * p_.dt;
  // The sample due at time ts is taken at the first step with t ≥ ts (t = n·dt exactly).
  while (out.next_sample_time() <= t + 1e-9 * p_.dt)
    out.sample({t, X_, V_, p_.slider.loading_force(t, X_), A_sum_, n_slipping_, n_intact_});
}

void ReferenceScheme::complete(RunObserver& out, const JunctionTotals& j, std::int64_t slips, bool any_repin,
                               std::int64_t force_evals) {
  const double dt = p_.dt;
  const std::int64_t n = n_ + 1;
  const double t = static_cast<double>(n) * dt;
  const double X1 = next_X();
  const double gamma1 = p_.slider.acceleration(p_.slider.loading_force(t, X1), j.F, V_);
  const double V1 = V_ + 0.5 * dt * (gamma_ + gamma1);
  if (!std::isfinite(X1) || !std::isfinite(V1))
    throw SolverError("reference: non-finite state at t = " + std::to_string(t) + " s");
  stats_.slips += slips;
  stats_.repins += any_repin;
  stats_.force_evals += force_evals;
  n_ = n;
  X_ = X1;
  V_ = V1;
  gamma_ = gamma1;
  A_sum_ = j.A;
  n_slipping_ = j.n_slipping;
  n_intact_ = j.n_intact;
  if (slips > 0 || any_repin) out.population({t, slips, any_repin, j.n_intact});
  // Extrema of Q: V crosses v between steps; Q is largest/smallest at the nearer step.
  const double v = p_.slider.v;
  const double Q = p_.slider.loading_force(t, X_);
  const double A = j.A;
  if (prevV_ < v && V_ >= v)
    out.extremum(Q >= prevQ_ ? Extremum{t, Q, A, true} : Extremum{prevt_, prevQ_, prevA_, true});
  if (prevV_ > v && V_ <= v)
    out.extremum(Q <= prevQ_ ? Extremum{t, Q, A, false} : Extremum{prevt_, prevQ_, prevA_, false});
  prevQ_ = Q;
  prevA_ = A;
  prevV_ = V_;
  prevt_ = t;
  emit_samples(out);
}

void ReferenceScheme::finish(RunInfo& info, double max_ratio) const {
  info.max_f_over_sigmaA = max_ratio;
  info.max_f_over_sigma_exp_A = max_ratio / p_.law.epsilon;
  info.stats = stats_;
  info.stats.steps = n_;
  info.t_end = static_cast<double>(n_) * p_.dt;
}

}  // namespace asperity
