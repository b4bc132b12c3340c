#pragma once
// Single-junction contact law of the paper (docs/model.md §1): Mindlin stiffness (Eq. 2),
// shear-induced area reduction (Eq. 3), static threshold. Pure functions, SI units.
#include <cmath>

namespace asperity {

enum class JunctionShape { elliptic, circular };
enum class AreaLaw { until_first_slip, always };

// Initial diameter ℓ0 [m] of a circular junction of area A0 [m²].
inline double initial_diameter(double area_m2) { return std::sqrt(4.0 * area_m2 / M_PI); }

// Dimensionless stiffness factor κ(r), r = A/A0 ∈ (0, 1]: k = ℓ0 E κ(r).
// Elliptic (Eq. 2) written with Carlson's symmetric integrals of the complementary modulus
// squared r² = (ℓ∥/ℓ⊥)² = 1 − e²:  K(e) = R_F(0, r², 1) and (K−E)/e² = R_D(0, r², 1)/3
// (the latter is exactly boost::math::ellint_d(e)). Taking r² as input keeps both ends exact:
// e → 0 (no 0/0) and e → 1 (1 − e² is not lost to rounding), where κ → 0 logarithmically.
double stiffness_factor(double area_ratio, double nu, JunctionShape shape);

// Eq. (2) directly from the two diameters [m] (ℓ∥ ≤ ℓ⊥); E [Pa].
double mindlin_stiffness(double ell_perp_m, double ell_par_m, double E_pa, double nu);

// Circle limit of Eq. (2): k = E ℓ / ((1+ν)(1−ν/2)) [N/m].
inline double circle_stiffness(double ell_m, double E_pa, double nu) {
  return E_pa * ell_m / ((1.0 + nu) * (1.0 - 0.5 * nu));
}

// Eq. (3): A = A0 − α_b f² / A0^p [m²]; may be ≤ 0 for forces beyond the law's range.
inline double sheared_area(double A0_m2, double f_n, double alpha_b, double p) {
  return A0_m2 - alpha_b * f_n * f_n / std::pow(A0_m2, p);
}

// Eq. (3) in the dimensionless force φ = s f (s = ContactLaw::force_scale): A = A0 (1 − φ²) [m²].
// The solvers, which work in φ (or ψ), call this one form.
inline double sheared_area_phi(double A0_m2, double phi) { return A0_m2 * (1.0 - phi * phi); }
// Its slope dA/dφ = −2 A0 φ [m²] (the interacting solver's dA/dX = dA/dφ · s · df/dX).
inline double sheared_area_phi_slope(double A0_m2, double phi) { return -2.0 * A0_m2 * phi; }

// Radius [m] of the disc of area A [m²] (a junction's footprint in the interaction kernel).
inline double disc_radius(double area_m2) { return std::sqrt(area_m2 / M_PI); }

// The parameters that turn areas into forces; one value shared by all junctions of a run.
struct ContactLaw {
  double E = 1.6e6;  // Pa
  double nu = 0.5;
  double sigma = 0.23e6 / 0.9;  // Pa, model shear strength σ = σ_exp/ε
  double epsilon = 0.9;         // slipping force / static threshold
  double alpha_b = 0.725e-15;   // m⁵/N² (for p = 1.5)
  double p = 1.5;
  JunctionShape shape = JunctionShape::elliptic;

  // k [N/m] of a junction with initial area A0 at current area A.
  double stiffness(double A0, double A) const { return initial_diameter(A0) * E * stiffness_factor(A / A0, nu, shape); }
  double area(double A0, double f) const { return sheared_area(A0, f, alpha_b, p); }
  // Largest |f| for which Eq. (3) leaves a positive area.
  double max_force(double A0) const { return std::sqrt(std::pow(A0, p + 1.0) / alpha_b); }
  // Scale s = sqrt(α_b / A0^(p+1)) [1/N] of the dimensionless force φ = s f (A/A0 = 1 − φ²).
  double force_scale(double A0) const { return std::sqrt(alpha_b / std::pow(A0, p + 1.0)); }
  // φ at the first slip of a never-slipped junction: φ = β(1 − φ²), β = σ sqrt(α_b A0^(1−p)).
  double slip_phi(double A0) const;

  // Solves f = k(A(f)) δ for a never-slipped junction at displacement δ [m] (odd in δ) by
  // bisection (the paper's "dichotomy", Boost.Math), to relative tolerance ~1e-15.
  double solve_pinned_force(double A0, double delta_m) const;
  // Solves f = ε σ A(f) (slipping junction whose area follows Eq. 3 at all times).
  double slipping_force_always(double A0) const;
};

}  // namespace asperity
