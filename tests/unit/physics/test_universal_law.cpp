#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <thread>
#include <vector>

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

TEST_CASE("universal_force_law: one immutable table per (ν, shape, range), the same as a fresh build", "[physics]") {
  const auto a = universal_force_law(0.5, JunctionShape::elliptic, 1.7);
  const auto b = universal_force_law(0.5, JunctionShape::elliptic, 1.7);
  CHECK(a.get() == b.get());  // built once
  CHECK(universal_force_law(0.5, JunctionShape::circular, 1.7).get() != a.get());
  CHECK(universal_force_law(0.5, JunctionShape::elliptic, 1.8).get() != a.get());
  // Second method: a table built here, outside the cache, over the same range is the same
  // piecewise cubic, so a run's numbers do not depend on the cache.
  const UniversalForceLaw fresh(0.5, JunctionShape::elliptic, 1.7);
  CHECK(a->nodes() == fresh.nodes());
  for (double psi : {1e-6, 0.3, 1.1, 1.69}) CHECK(a->g(psi) == fresh.g(psi));
  CHECK_THAT(a->g(1.1), WithinRel(a->g_exact(1.1), 1e-13));
  // A tiny range is widened to 1e-3, where the spline fit is accurate.
  const auto tiny = universal_force_law(0.5, JunctionShape::elliptic, 1e-9);
  CHECK(tiny->psi_max() == 1e-3);
  CHECK(tiny->max_rel_error() < 1e-13);
}

TEST_CASE("universal_force_law: concurrent first callers share one table", "[physics]") {
  std::vector<std::shared_ptr<const UniversalForceLaw>> got(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&got, i] { got[i] = universal_force_law(0.3, JunctionShape::elliptic, 0.77); });
  for (auto& t : threads) t.join();
  for (const auto& g : got) CHECK(g.get() == got[0].get());
  // ν = 0.3 at ψ = 0: g = κ(1) = 1/((1+ν)(1−ν/2)), the circle limit.
  CHECK_THAT(got[0]->g(0.0), WithinRel(1.0 / (1.3 * 0.85), 1e-15));
}

TEST_CASE("universal_psi is ψ = φ/κ(1 − φ²) and the table's ψ(φ)", "[physics]") {
  const UniversalForceLaw U(0.5, JunctionShape::circular, 2.0);
  for (double phi : {0.1, 0.5, 0.9}) {
    // Circular junction: κ(r) = sqrt(r)/((1+ν)(1−ν/2)), closed form.
    const double expected = phi * 1.5 * 0.75 / std::sqrt(1 - phi * phi);
    CHECK_THAT(universal_psi(phi, 0.5, JunctionShape::circular), WithinRel(expected, 1e-15));
    CHECK(U.psi_of_phi(phi) == universal_psi(phi, 0.5, JunctionShape::circular));
  }
}
