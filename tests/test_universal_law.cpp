#include <catch2/catch.hpp>

#include "physics/universal_law.hpp"

using namespace asperity;
using Catch::Matchers::WithinRel;

TEST_CASE("universal law gives the bisection force of every junction", "[physics]") {
  for (auto shape : {JunctionShape::elliptic, JunctionShape::circular}) {
    ContactLaw law;
    law.shape = shape;
    const UniversalForceLaw U(law.nu, shape, 6.0);
    CHECK(U.max_rel_error() < 1e-13);
    for (double A0 : {1e-12, 1e-9, 1e-8, 1e-7}) {
      const double w = initial_diameter(A0) * law.E, c = w * law.force_scale(A0);
      const double phi_s = law.slip_phi(A0);
      const double d_s = U.psi_of_phi(phi_s) / c;
      for (double frac : {0.01, 0.3, 0.7, 1.0}) {
        const double d = frac * d_s;
        const double f_table = w * d * U.g(c * d);
        // Second method: the paper's per-junction bisection.
        CHECK_THAT(f_table, WithinRel(law.solve_pinned_force(A0, d), 3e-13));  // measured 6.6e-14
      }
    }
  }
}

TEST_CASE("universal law: inverse of ψ(φ) and evenness", "[physics]") {
  const UniversalForceLaw U(0.5, JunctionShape::elliptic, 4.0);
  for (double phi : {1e-9, 0.2, 0.6, 0.95}) {
    CHECK_THAT(U.phi_of_psi_exact(U.psi_of_phi(phi)), WithinRel(phi, 1e-15));  // measured 2.2e-16
  }
  CHECK(U.g(-1.3) == U.g(1.3));
  CHECK_THAT(U.g(0.0), WithinRel(1.0 / (1.5 * 0.75), 1e-15));  // measured 0
  // Beyond the table the exact inverse takes over.
  CHECK_THAT(U.g(9.0), WithinRel(U.phi_of_psi_exact(9.0) / 9.0, 1e-15));
}
