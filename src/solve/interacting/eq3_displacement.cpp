#include "solve/interacting/eq3_displacement.hpp"

#include <algorithm>
#include <cmath>

#include "solve/interacting/solver_failure.hpp"

namespace asperity {

Eq3Displacement::Eq3Displacement(const ContactLaw& law, const std::vector<double>& A0_m2) : law_(&law) {
  const std::size_t N = A0_m2.size();
  c_.assign(N, 0.0);
  s_.assign(N, 0.0);
  f_slip_.assign(N, 0.0);
  phi_last_.assign(N, 0.0);
  psi_last_.assign(N, 0.0);
  dpsi_last_.assign(N, 0.0);
  double psi_hi = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double A0 = A0_m2[i];
    s_[i] = law.force_scale(A0);
    c_[i] = initial_diameter(A0) * law.E * s_[i];
    psi_hi = std::max(psi_hi, universal_psi(law.slip_phi(A0), law.nu, law.shape));
    f_slip_[i] = law.slip_phi(A0) / s_[i];
  }
  table_ = universal_force_law(law.nu, law.shape, 1.1 * psi_hi);
  if (!(table_->max_rel_error() <= 1e-11))
    interacting_solver_failure("the universal force law's table is not accurate enough", 0.0);
}

void Eq3Displacement::at(std::size_t i, double f, double& u, double& du) {
  // Universal law: φ = s f = ψ g(ψ) (the tabulated inverse of ψ = φ/κ(1 − φ²)), u = ψ/c, so
  // ψ by Newton on the table, from the tangent at the junction's last call: successive calls
  // move φ by little (a chord pass, a nearby X), so the start is within O(Δφ²) and Newton's
  // first step usually already meets the stopping rule (one table evaluation instead of two or
  // three from the last ψ itself).
  const double lim = 1.0 - 1e-12;
  const double phi = std::clamp(s_[i] * f, -lim, lim);
  double psi = psi_last_[i] + (phi - phi_last_[i]) * dpsi_last_[i];
  if (!(std::abs(psi) < table_->psi_max())) psi = psi_last_[i];  // never start outside the table
  double d[4];
  double dpsi = 0;
  bool ok = false;
  for (int it = 0; it < 8; ++it) {
    if (!table_->g_derivatives(psi, d)) break;
    dpsi = 1.0 / (d[0] + psi * d[1]);
    const double step = (psi * d[0] - phi) * dpsi;
    psi -= step;
    // Converged: dψ/dφ from this last evaluation, a step of ≤ 1e-15 away (a relative change of
    // that order in du; one table evaluation fewer per call).
    if (std::abs(step) <= 1e-15 * std::abs(psi)) {
      ok = true;
      break;
    }
  }
  if (!ok) {  // beyond the table (far past the slip force): the exact law
    psi = universal_psi(phi, law_->nu, law_->shape);
    const double h = 1e-6;
    const double p1 = std::min(phi + h, lim), p0 = std::max(phi - h, -lim);
    dpsi = (universal_psi(p1, law_->nu, law_->shape) - universal_psi(p0, law_->nu, law_->shape)) / (p1 - p0);
  }
  phi_last_[i] = phi, psi_last_[i] = psi, dpsi_last_[i] = dpsi;
  u = psi / c_[i];
  du = dpsi * s_[i] / c_[i];
}

}  // namespace asperity
