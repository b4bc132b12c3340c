#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/math/special_functions/ellint_d.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "physics/contact_law.hpp"

using namespace asperity;
using Catch::Matchers::WithinRel;

TEST_CASE("Eq. 2 reduces to the circle formula when the junction is round", "[physics]") {
  for (double ell : {1e-6, 3.3e-5, 1e-3}) {
    const double k = mindlin_stiffness(ell, ell, 1.6e6, 0.5);
    CHECK_THAT(k, WithinRel(circle_stiffness(ell, 1.6e6, 0.5), 1e-14));
  }
  // ν = 0.3 as well: the circle formula is not special to ν = 1/2.
  CHECK_THAT(mindlin_stiffness(1e-4, 1e-4, 2e6, 0.3), WithinRel(circle_stiffness(1e-4, 2e6, 0.3), 1e-14));
}

TEST_CASE("Carlson form of Eq. 2 matches Legendre's K and E for a mid eccentricity", "[physics]") {
  for (double e : {0.3, 0.7, 0.95}) {
    const double r = std::sqrt(1 - e * e);  // ℓ∥/ℓ⊥
    const double K = boost::math::ellint_1(e), E = boost::math::ellint_2(e), nu = 0.5;
    const double legendre = 0.5 * M_PI / ((1 + nu) * (K - nu / (e * e) * (K - E)));
    CHECK_THAT(stiffness_factor(r, nu, JunctionShape::elliptic), WithinRel(legendre, 1e-13));
  }
}

TEST_CASE("(K−E)/e² is finite and exact at e = 0 and e = 1e-8", "[physics]") {
  // Series D(e) = π/4 (1 + 3e²/8 + ...): at e = 1e-8 the correction is below 1e-16.
  CHECK_THAT(boost::math::ellint_d(0.0), WithinRel(M_PI / 4, 1e-15));
  CHECK_THAT(boost::math::ellint_d(1e-8), WithinRel(M_PI / 4, 1e-15));
  // Our stiffness at r = A/A0 giving e = 1e-8 equals the circle value (no 0/0).
  const double e = 1e-8, r = std::sqrt(1 - e * e);
  CHECK_THAT(stiffness_factor(r, 0.5, JunctionShape::elliptic), WithinRel(1.0 / (1.5 * 0.75), 1e-15));
  CHECK(std::isfinite(stiffness_factor(1.0, 0.5, JunctionShape::elliptic)));
}

TEST_CASE("k → 0 as A → 0, following K ≈ ln(4/r)", "[physics]") {
  const double nu = 0.5;
  double prev = stiffness_factor(1.0, nu, JunctionShape::elliptic);
  for (double r : {1e-1, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15}) {
    const double kap = stiffness_factor(r, nu, JunctionShape::elliptic);
    CHECK(kap < prev);
    prev = kap;
    if (r <= 1e-9) {  // asymptote: K ≈ ln(4/r), E ≈ 1, so K − ν(K − E) ≈ (1−ν) ln(4/r) + ν
      const double L = std::log(4 / r);
      CHECK_THAT(kap, WithinRel(0.5 * M_PI / ((1 + nu) * ((1 - nu) * L + nu)), 1e-15));  // measured 2.2e-16
    }
  }
  CHECK(stiffness_factor(0.0, nu, JunctionShape::elliptic) == 0.0);
  CHECK(prev < 0.07 * stiffness_factor(1.0, nu, JunctionShape::elliptic));
}

TEST_CASE("bisection force satisfies f = k(A(f)) δ and is odd in δ", "[physics]") {
  ContactLaw law;
  for (double A0 : {1e-14, 1e-9, 1e-8, 1e-7, 1e-4}) {
    const double fmax = law.max_force(A0);
    const double k0 = law.stiffness(A0, A0);
    for (double frac : {1e-6, 0.1, 0.5, 0.9, 0.999}) {
      // A displacement whose force is frac·f_max: δ = f / k(A(f)).
      const double f_true = frac * fmax;
      const double delta = f_true / law.stiffness(A0, law.area(A0, f_true));
      const double f = law.solve_pinned_force(A0, delta);
      CHECK_THAT(f, WithinRel(law.stiffness(A0, law.area(A0, f)) * delta, 1e-13));  // measured 2.9e-14
      CHECK_THAT(f, WithinRel(f_true, 1e-15));                                      // measured 2.2e-16
      CHECK(law.solve_pinned_force(A0, -delta) == -f);
      CHECK(f <= k0 * delta);
    }
  }
}

TEST_CASE("slip point φ_s solves φ = β(1 − φ²), i.e. f = σ A(f)", "[physics]") {
  ContactLaw law;
  for (double A0 : {1e-14, 1e-9, 1e-7, 1e-4}) {
    const double phi = law.slip_phi(A0);
    const double f = phi / law.force_scale(A0);
    CHECK_THAT(f, WithinRel(law.sigma * law.area(A0, f), 3e-14));  // measured 6.0e-15
  }
  law.alpha_b = 1e-30;  // tiny α_b: the series branch, f_s → σ A0
  CHECK_THAT(law.slip_phi(1e-8) / law.force_scale(1e-8), WithinRel(law.sigma * 1e-8, 3e-15));  // measured 6.7e-16
}

TEST_CASE("slipping force of the always variant solves f = εσA(f)", "[physics]") {
  ContactLaw law;
  for (double A0 : {1e-12, 1e-8, 1e-5}) {
    const double f = law.slipping_force_always(A0);
    CHECK_THAT(f, WithinRel(law.epsilon * law.sigma * law.area(A0, f), 2e-15));  // measured 3.3e-16
  }
}
