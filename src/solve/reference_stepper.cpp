// Each junction changes state at most once per step (pinned → slipping, or slipping → pinned),
// as the paper's scan does.
#include "solve/reference_stepper.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "physics/interface_law.hpp"

namespace asperity {

double reference_spectral_radius(double omega_dt, double eta_dt) {
  // Variables (X, h V, h² γ) for X'' = −ω² X − η Ẋ; the same map as the step below.
  const double a = omega_dt * omega_dt, b = eta_dt;
  // Eigen's eigensolver does not return on a matrix with inf or NaN (an absurd dt).
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix3d m;
  // x1 = x + u + g/2;  g1 = −a x1 − b u;  u1 = u + (g + g1)/2
  m << 1, 1, 0.5,                           // x1
      -0.5 * a, 1 - 0.5 * a - 0.5 * b, 0.5 - 0.25 * a,  // u1
      -a, -a - b, -0.5 * a;                 // g1
  return m.eigenvalues().cwiseAbs().maxCoeff();
}

ReferenceStepper::ReferenceStepper(const Problem& problem)
    : p_(problem), J_(problem.A0, problem.law) {
  const double dt = p_.dt;
  const double rho = reference_spectral_radius(std::sqrt((p_.K0 + p_.slider.k_L) / p_.slider.mass_kg) * dt,
                                               p_.slider.eta * dt);
  if (rho > 1.0 + 1e-12) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "reference step unstable: spectral radius %.6g > 1 at dt = %.6g s (raise solver.Ct or lower model.eta)",
                  rho, dt);
    throw SolverError(msg);
  }
  n_end_ = static_cast<std::int64_t>(std::ceil(p_.t_stop / dt - 1e-9));
  A_sum_ = p_.A0_sum;
  prevA_ = p_.A0_sum;
  n_intact_ = static_cast<std::int64_t>(J_.size());
}

void ReferenceStepper::emit_samples(RunObserver& out) const {
  const double t = static_cast<double>(n_) * p_.dt;
  // The sample due at time ts is taken at the first step with t ≥ ts (t = n·dt exactly).
  while (out.next_sample_time() <= t + 1e-9 * p_.dt)
    out.sample({t, X_, V_, p_.slider.loading_force(t, X_), A_sum_, n_slipping_, n_intact_});
}

void ReferenceStepper::start(RunObserver& out) { emit_samples(out); }

void ReferenceStepper::advance(RunObserver& out) {
  const ContactLaw& law = p_.law;
  const AreaLaw area_law = p_.area_law;
  const bool always = area_law == AreaLaw::always;
  const double dt = p_.dt;
  JunctionState& J = J_;
  const std::size_t N = J.size();
  const std::int64_t n = n_ + 1;
  const double t = static_cast<double>(n) * dt;
  const double X1 = X_ + dt * V_ + 0.5 * dt * dt * gamma_;
  const bool slow = std::abs(V_) < p_.repin_speed();  // |Ẋ(t)|: the latest known velocity
  std::int64_t slips = 0;
  bool any_repin = false;
  // Fork only when the junctions outweigh the fork-join cost (~µs per step): at N = 60 two
  // threads were 8× slower than one (bench report).
#pragma omp parallel for schedule(static) reduction(+ : slips) reduction(|| : any_repin) if (N >= 256)
  for (std::size_t i = 0; i < N; ++i) {
    double f;
    if (J.pinned[i]) {
      if (area_follows_force(area_law, J.intact[i])) {
        f = law.solve_pinned_force(J.A0[i], X1 - J.anchor[i]);
        J.set_contact(i, contact_at_force(law, J.A0[i], f));
      } else {
        f = pinned_force(J.k[i], X1, J.anchor[i]);
      }
      if (starts_to_slip(f, J.f_s[i])) {
        J.pinned[i] = 0;
        J.intact[i] = 0;
        f = slipping_force(law, area_law, J.A0[i], J.f_s[i]);
        if (always) J.set_contact(i, contact_at_force(law, J.A0[i], f));
        ++slips;
      }
    } else {
      f = J.force[i];
      if (slow) {  // repins with no force jump
        J.pinned[i] = 1;
        J.anchor[i] = repin_anchor(X1, f, J.k[i]);
        any_repin = true;
      }
    }
    J.force[i] = f;
  }
  // Serial sums in index order: the result does not depend on the thread count.
  double F = 0, A = 0;
  std::int64_t ns = 0, ni = 0;
  for (std::size_t i = 0; i < N; ++i) {
    F += J.force[i];
    A += J.area[i];
    ns += !J.pinned[i];
    ni += J.intact[i];
    const double r = J.force[i] / (law.sigma * J.area[i]);
    if (r > max_ratio_) max_ratio_ = r;
  }
  const double gamma1 = p_.slider.acceleration(p_.slider.loading_force(t, X1), F, V_);
  const double V1 = V_ + 0.5 * dt * (gamma_ + gamma1);
  if (!std::isfinite(X1) || !std::isfinite(V1))
    throw SolverError("reference: non-finite state at t = " + std::to_string(t) + " s");
  stats_.slips += slips;
  stats_.repins += any_repin;
  stats_.force_evals += 1;
  n_ = n;
  X_ = X1;
  V_ = V1;
  gamma_ = gamma1;
  A_sum_ = A;
  n_slipping_ = ns;
  n_intact_ = ni;
  if (slips > 0 || any_repin) out.population({t, slips, any_repin, ni});
  // Extrema of Q: V crosses v between steps; Q is largest/smallest at the nearer step.
  const double v = p_.slider.v;
  const double Q = p_.slider.loading_force(t, X_);
  if (prevV_ < v && V_ >= v) out.extremum(Q >= prevQ_ ? Extremum{t, Q, A, true} : Extremum{prevt_, prevQ_, prevA_, true});
  if (prevV_ > v && V_ <= v) out.extremum(Q <= prevQ_ ? Extremum{t, Q, A, false} : Extremum{prevt_, prevQ_, prevA_, false});
  prevQ_ = Q;
  prevA_ = A;
  prevV_ = V_;
  prevt_ = t;
  emit_samples(out);
}

void ReferenceStepper::finish(RunInfo& info) const {
  info.max_f_over_sigmaA = max_ratio_;
  info.max_f_over_sigma_exp_A = max_ratio_ / p_.law.epsilon;
  info.stats = stats_;
  info.stats.steps = n_;
  info.t_end = static_cast<double>(n_) * p_.dt;
}

}  // namespace asperity
