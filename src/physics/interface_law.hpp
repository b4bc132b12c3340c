#pragma once
// The junction interface law (docs/model.md §1): when a pinned junction starts to slip, the force
// it carries while slipping, where it repins, and how its area, stiffness and static threshold
// follow the force under both area laws and both shapes (the shape enters through
// ContactLaw::stiffness). Both solvers call these; pure functions, SI units.
#include "physics/contact_law.hpp"

namespace asperity {

// What the area of a junction fixes: area A [m²], tangential stiffness k(A) [N/m], static
// threshold f_s = σ A [N].
struct JunctionContact {
  double area_m2 = 0, k = 0, f_s = 0;
};

// The contact of a junction of initial area A0 at current area A.
inline JunctionContact contact_at_area(const ContactLaw& law, double A0, double A) {
  return {A, law.stiffness(A0, A), law.sigma * A};
}

// The contact of a junction whose area follows Eq. (3) while it carries force f.
inline JunctionContact contact_at_force(const ContactLaw& law, double A0, double f) {
  return contact_at_area(law, A0, law.area(A0, f));
}

// The contact a never-slipped junction freezes at its first slip (area_law: until_first_slip),
// taken at the exact slip point f = f_s = σ A: A = A0 (1 − φ_s²) (A0 itself when α_b = 0).
inline JunctionContact contact_at_first_slip(const ContactLaw& law, double A0) {
  const double phi_s = law.slip_phi(A0);
  return contact_at_area(law, A0, A0 * (1.0 - phi_s * phi_s));
}

// Eq. (3) holds for a pinned junction that has never slipped, or at all times (area_law: always).
inline bool area_follows_force(AreaLaw area_law, bool intact) { return intact || area_law == AreaLaw::always; }

// Force of a pinned junction with constant stiffness k anchored at x, at slider position X.
inline double pinned_force(double k, double X_m, double anchor_m) { return k * (X_m - anchor_m); }

// Slip condition: a pinned junction starts to slip once its force reaches the static threshold.
inline bool starts_to_slip(double f_n, double f_s_n) { return f_n >= f_s_n; }

// Slider position at which a pinned junction of constant stiffness k anchored at x slips.
inline double slip_position(double anchor_m, double f_s_n, double k) { return anchor_m + f_s_n / k; }

// Force of a slipping junction: ε f_s, its threshold when it started to slip; under area_law:
// always the solution of f = ε σ A(f), whose contact is contact_at_force(law, A0, f).
inline double slipping_force(const ContactLaw& law, AreaLaw area_law, double A0, double f_s_n) {
  return area_law == AreaLaw::always ? law.slipping_force_always(A0) : law.epsilon * f_s_n;
}

// Anchor of a junction that repins at slider position X carrying force f with stiffness k:
// x = X − f/k, so its force does not jump.
inline double repin_anchor(double X_m, double f_n, double k) { return X_m - f_n / k; }

}  // namespace asperity
