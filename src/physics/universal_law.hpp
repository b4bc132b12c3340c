#pragma once
// The universal dimensionless force law of a never-slipped junction (docs/model.md §4).
// With φ = s f, s = sqrt(α_b / A0^(p+1)) (so A/A0 = 1 − φ²) and ψ = s ℓ0 E δ, Eq. (2)+(3)
// reduce to ψ = φ / κ(1 − φ²): one increasing function per (ν, shape) for every junction,
// p, α_b and E. Its inverse gives the force at any displacement without a per-junction
// root solve: f = ℓ0 E δ g(ψ), with g(ψ) = Φ(ψ)/ψ = κ(A/A0) the current stiffness factor.
#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "physics/contact_law.hpp"

namespace asperity {

// ψ(φ) = φ / κ(1 − φ²): the dimensionless displacement of a never-slipped junction carrying
// the dimensionless force φ (explicit and increasing on [0, 1)).
inline double universal_psi(double phi, double nu, JunctionShape shape) {
  return phi / stiffness_factor(1.0 - phi * phi, nu, shape);
}

class UniversalForceLaw {
 public:
  // Tabulates g on ψ ∈ [0, psi_max], refining until the relative interpolation error,
  // checked against the exact inverse between the nodes, is below rel_tol.
  UniversalForceLaw(double nu, JunctionShape shape, double psi_max, double rel_tol = 1e-13);

  double psi_of_phi(double phi) const { return universal_psi(phi, nu_, shape_); }
  double phi_of_psi_exact(double psi) const;  // root solve (Boost.Math TOMS 748)
  // g(ψ) = κ(A/A0): from the table inside its range, exactly beyond it.
  double g(double psi) const {
    const double a = psi < 0 ? -psi : psi;  // g is even
    if (!(a < psi_max_)) return g_exact(a);
    const double u = a * inv_h_;
    const std::size_t j = std::min(static_cast<std::size_t>(u), coef_.size() - 1);
    const double t = u - static_cast<double>(j);
    const auto& c = coef_[j];
    return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
  }
  double g_exact(double psi) const;
  // g and its first three derivatives at ψ (inside the table: the interpolating cubic's own,
  // so a Taylor sum of order 3 reproduces g exactly within one table interval). Returns false
  // beyond the table, where no derivative is provided.
  bool g_derivatives(double psi, double d[4]) const {
    const double a = psi < 0 ? -psi : psi;
    if (!(a < psi_max_)) return false;
    const double u = a * inv_h_;
    const std::size_t j = std::min(static_cast<std::size_t>(u), coef_.size() - 1);
    const double t = u - static_cast<double>(j);
    const auto& c = coef_[j];
    const double s = psi < 0 ? -1.0 : 1.0;  // g even: odd derivatives change sign
    d[0] = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    d[1] = s * (c[1] + t * (2 * c[2] + t * 3 * c[3])) * inv_h_;
    d[2] = (2 * c[2] + 6 * c[3] * t) * inv_h_ * inv_h_;
    d[3] = s * 6 * c[3] * inv_h_ * inv_h_ * inv_h_;
    return true;
  }
  double psi_max() const { return psi_max_; }
  std::size_t nodes() const { return nodes_; }
  double max_rel_error() const { return max_err_; }

 private:
  double nu_;
  JunctionShape shape_;
  double psi_max_;
  std::size_t nodes_ = 0;
  double max_err_ = 0;
  double inv_h_ = 0;
  // Boost's cubic B-spline through the exact values, stored per interval in power form: the
  // same piecewise cubic, evaluated in a few ns in the solver's innermost loop.
  std::vector<std::array<double, 4>> coef_;
};

// The process-wide table for (ν, shape) covering ψ ∈ [0, max(psi_max, 1e-3)]: built on first
// use, then shared, immutable, by every run of the process that asks for the same range (a
// build costs milliseconds, a short run about as much). The range is never rounded, so a run
// gets the very table it built before this cache existed: its numbers do not change, and do
// not depend on which runs came before. At least 1e-3: a table over a tiny range (slip
// thresholds of ψ < 1e-6, e.g. sigma_exp = 1e-2 Pa) comes out of the spline fit wrong by
// orders of magnitude (force 1e10 times too stiff: a run crawled at 1e-9 s steps), while g is as
// smooth on [0, 1e-3]. Thread-safe; a table stays alive
// while a caller holds it.
std::shared_ptr<const UniversalForceLaw> universal_force_law(double nu, JunctionShape shape, double psi_max);

}  // namespace asperity
