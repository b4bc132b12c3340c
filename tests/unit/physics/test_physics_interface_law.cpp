// physics/interface_law.hpp: slip condition, slipping force, repinning and the contact of a
// junction under both area laws and both shapes, checked against Eq. (2), (3) and docs/model.md §1.
#include <catch2/catch.hpp>
#include <cmath>

#include "physics/interface_law.hpp"

using namespace asperity;
using Catch::Matchers::WithinRel;

TEST_CASE("interface law: an unloaded junction has its initial contact (circle formula)", "[physics]") {
  ContactLaw law;
  law.shape = JunctionShape::circular;
  const double A0 = 1e-8;
  const JunctionContact c = contact_at_force(law, A0, 0.0);
  CHECK(c.area_m2 == A0);
  CHECK_THAT(c.k, WithinRel(law.E * std::sqrt(4 * A0 / M_PI) / (1.5 * 0.75), 1e-14));  // measured 2.2e-16
  CHECK_THAT(c.f_s, WithinRel(law.sigma * A0, 1e-15));
}

TEST_CASE("interface law: the first slip happens at f = σ A(f), on the bisection force curve", "[physics]") {
  for (auto shape : {JunctionShape::elliptic, JunctionShape::circular}) {
    ContactLaw law;
    law.shape = shape;
    for (double A0 : {1e-10, 1e-8, 1e-7}) {
      const JunctionContact c = contact_at_first_slip(law, A0);
      // The frozen area obeys Eq. (3) at the threshold force f_s = σ A.
      CHECK_THAT(c.area_m2, WithinRel(law.area(A0, c.f_s), 4e-15));  // measured 8.9e-16
      // Second method: the bisection force at displacement f_s/k is f_s (the junction slips there).
      const double d = c.f_s / c.k;
      CHECK_THAT(law.solve_pinned_force(A0, d), WithinRel(c.f_s, 1e-15));  // measured 2.2e-16
      CHECK(starts_to_slip(c.f_s, c.f_s));
      CHECK_FALSE(starts_to_slip(std::nextafter(c.f_s, 0.0), c.f_s));
    }
  }
  // Without shear-induced area reduction the junction slips at its initial area.
  ContactLaw linear;
  linear.alpha_b = 0;
  CHECK(contact_at_first_slip(linear, 1e-8).area_m2 == 1e-8);
}

TEST_CASE("interface law: slipping force ε f_s, or f = ε σ A(f) under area_law: always", "[physics]") {
  const ContactLaw law;
  const double A0 = 5e-8, f_s = law.sigma * A0;
  CHECK_THAT(slipping_force(law, AreaLaw::until_first_slip, A0, f_s), WithinRel(0.9 * f_s, 1e-15));
  const double f = slipping_force(law, AreaLaw::always, A0, f_s);
  CHECK_THAT(f, WithinRel(law.epsilon * law.sigma * law.area(A0, f), 1e-15));  // the fixed point; measured 2.2e-16
  CHECK(f < 0.9 * f_s);  // the area has shrunk under the slipping force
}

TEST_CASE("interface law: repinning keeps the force, and the next slip is f_s/k further", "[physics]") {
  const double k = 3.7e3, f = 0.0123, X = 2.5e-5;
  const double x = repin_anchor(X, f, k);
  CHECK_THAT(pinned_force(k, X, x), WithinRel(f, 1e-14));  // no force jump; measured 2.2e-16
  const double f_s = f / 0.9;
  CHECK_THAT(pinned_force(k, slip_position(x, f_s, k), x), WithinRel(f_s, 1e-14));  // measured 2.2e-16
  CHECK(area_follows_force(AreaLaw::until_first_slip, true));
  CHECK_FALSE(area_follows_force(AreaLaw::until_first_slip, false));
  CHECK(area_follows_force(AreaLaw::always, false));
}
