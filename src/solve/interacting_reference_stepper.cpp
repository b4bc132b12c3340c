#include "solve/interacting_reference_stepper.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/interface_law.hpp"
#include "solve/reference_stepper.hpp"

namespace asperity {

InteractingReferenceStepper::InteractingReferenceStepper(const Problem& problem)
    : p_(problem), C_(interaction_matrix(problem)), forces_(problem, C_), J_(problem.A0, problem.law) {
  const double dt = p_.dt;
  // K0 (independent junctions) bounds the interacting stiffness from above: the same check.
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

void InteractingReferenceStepper::emit_samples(RunObserver& out) const {
  const double t = static_cast<double>(n_) * p_.dt;
  while (out.next_sample_time() <= t + 1e-9 * p_.dt)
    out.sample({t, X_, V_, p_.slider.loading_force(t, X_), A_sum_, n_slipping_, n_intact_});
}

void InteractingReferenceStepper::start(RunObserver& out) { emit_samples(out); }

void InteractingReferenceStepper::advance(RunObserver& out) {
  const ContactLaw& law = p_.law;
  const AreaLaw area_law = p_.area_law;
  const double dt = p_.dt;
  JunctionState& J = J_;
  const std::size_t N = J.size();
  const std::int64_t n = n_ + 1;
  const double t = static_cast<double>(n) * dt;
  const double X1 = X_ + dt * V_ + 0.5 * dt * dt * gamma_;
  const bool slow = std::abs(V_) < p_.repin_speed();

  // (1) Repinning junctions hold their force this step; (2)–(3) solve the pinned, slip, repeat.
  std::vector<std::uint8_t> repinning(N, 0), solve(N, 0);
  bool any_repin = false;
  for (std::size_t i = 0; i < N; ++i) {
    if (!J.pinned[i] && slow) repinning[i] = 1, any_repin = true;
    solve[i] = J.pinned[i];
  }
  std::int64_t slips = 0;
  for (;;) {
    stats_.force_evals += forces_.solve(J, solve, X1);
    std::int64_t new_slips = 0;
    for (std::size_t i = 0; i < N; ++i)
      if (solve[i] && starts_to_slip(J.force[i], J.f_s[i])) {
        solve[i] = 0;
        J.pinned[i] = 0;
        J.intact[i] = 0;
        J.force[i] = slipping_force(law, area_law, J.A0[i], J.f_s[i]);
        if (area_law == AreaLaw::always) J.set_contact(i, contact_at_force(law, J.A0[i], J.force[i]));
        ++new_slips;
      }
    slips += new_slips;
    if (new_slips == 0) break;
  }
  // (4) Anchors of the repinned junctions: X − x_i = f_i/k_i + Σ_{j≠i} C_ij f_j.
  for (std::size_t i = 0; i < N; ++i)
    if (repinning[i]) {
      double u = 0;
      for (std::size_t j = 0; j < N; ++j) u += C_(i, j) * J.force[j];
      J.anchor[i] = repin_anchor(X1, J.force[i], J.k[i]) - u;
      J.pinned[i] = 1;
    }

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
    throw SolverError("interacting reference: non-finite state at t = " + std::to_string(t) + " s");
  stats_.slips += slips;
  stats_.repins += any_repin;
  n_ = n;
  X_ = X1;
  V_ = V1;
  gamma_ = gamma1;
  A_sum_ = A;
  n_slipping_ = ns;
  n_intact_ = ni;
  if (slips > 0 || any_repin) out.population({t, slips, any_repin, ni});
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

void InteractingReferenceStepper::finish(RunInfo& info) const {
  info.max_f_over_sigmaA = max_ratio_;
  info.max_f_over_sigma_exp_A = max_ratio_ / p_.law.epsilon;
  info.stats = stats_;
  info.stats.steps = n_;
  info.t_end = static_cast<double>(n_) * p_.dt;
}

}  // namespace asperity
