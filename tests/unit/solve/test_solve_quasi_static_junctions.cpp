// solve/quasi_static/junction_curve.hpp: the junction models' quasi-static F(X) at α_b = 0, ε = 1
// against their own closed forms: independent junctions, Σ min(k_i X, σ A_i); two interacting
// junctions, the 2 × 2 system piece by piece.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "physics/contact_law.hpp"
#include "physics/elastic_interaction.hpp"
#include "solve/quasi_static/junction_curve.hpp"

using namespace asperity;

namespace {
constexpr double kE = 1.6e6, kNu = 0.5, kSigma = 0.25e6;
double stiffness(double area) { return circle_stiffness(initial_diameter(area), kE, kNu); }
}  // namespace

TEST_CASE("independent junctions at alpha_b = 0: F(X) = sum of min(k_i X, sigma A_i)", "[solve][quasi_static]") {
  QuasiStaticJunctions j;
  j.area_m2 = {1e-8, 4e-8, 2.5e-9, 9e-8, 1.6e-7};
  j.x_m = {0, 1e-3, 2e-3, 3e-3, 4e-3};
  j.y_m.assign(5, 0.0);
  j.E_Pa = kE, j.nu = kNu, j.shear_strength_Pa = kSigma;
  double k0 = 0, x_full = 0;
  for (const double a : j.area_m2) k0 += stiffness(a), x_full = std::max(x_full, kSigma * a / stiffness(a));
  std::vector<double> X;
  for (int i = 1; i <= 12; ++i) X.push_back(x_full * i / 10.0);
  const JunctionCurve c = quasi_static_junction_curve(j, X);
  CHECK_THAT(c.initial_stiffness_N_per_m, Catch::Matchers::WithinRel(k0, 1e-12));
  CHECK_THAT(c.full_sliding_displacement_m, Catch::Matchers::WithinRel(x_full, 1e-14));
  CHECK(c.monotone);
  for (std::size_t i = 0; i < X.size(); ++i) {
    double F = 0, slip = 0, total = 0;
    for (const double a : j.area_m2) {
      F += std::min(stiffness(a) * X[i], kSigma * a);
      // The CG stops within 1e-10 of X: a junction at its threshold within that counts either way.
      slip += stiffness(a) * X[i] > kSigma * a * (1 + 1e-9) ? a : 0, total += a;
    }
    REQUIRE(c.points[i].converged);
    CHECK_THAT(c.points[i].force_N, Catch::Matchers::WithinRel(F, 1e-9));
    CHECK(std::abs(c.points[i].slip_area_fraction - slip / total) < 1e-12);
  }
}

TEST_CASE("two interacting junctions at alpha_b = 0 follow their 2 x 2 system", "[solve][quasi_static]") {
  // Both stick: f = C⁻¹ X 1. The one whose stick force reaches σA first (the smaller) slips and
  // keeps σA_1; the other then carries f_2 = (X − C_21 σA_1) / C_22 until it reaches σA_2.
  for (const TractionWeighting w : {TractionWeighting::uniform, TractionWeighting::rigid}) {
    QuasiStaticJunctions j;
    j.area_m2 = {1e-8, 4e-8};
    j.x_m = {0, 3e-4};
    j.y_m = {0, 1e-4};
    j.E_Pa = kE, j.nu = kNu, j.shear_strength_Pa = kSigma, j.interacting = true, j.weighting = w;
    const double c11 = 1 / stiffness(j.area_m2[0]), c22 = 1 / stiffness(j.area_m2[1]);
    const double c12 = disc_compliance(-3e-4, -1e-4, disc_radius(1e-8), disc_radius(4e-8), kE, kNu, w);
    const double det = c11 * c22 - c12 * c12;
    const double s1 = (c22 - c12) / det, s2 = (c11 - c12) / det;  // stick forces per unit X
    const double b1 = kSigma * j.area_m2[0], b2 = kSigma * j.area_m2[1];
    REQUIRE(b1 / s1 < b2 / s2);  // junction 1 slips first
    const double X1 = b1 / s1, X2 = c22 * b2 + c12 * b1;
    const std::vector<double> X = {0.5 * X1, 0.999 * X1, 0.5 * (X1 + X2), 0.999 * X2, 1.5 * X2};
    const JunctionCurve c = quasi_static_junction_curve(j, X);
    CHECK_THAT(c.initial_stiffness_N_per_m, Catch::Matchers::WithinRel(s1 + s2, 1e-10));
    CHECK_THAT(c.full_sliding_displacement_m, Catch::Matchers::WithinRel(X2, 1e-12));
    const double expected[] = {(s1 + s2) * X[0], (s1 + s2) * X[1], b1 + (X[2] - c12 * b1) / c22,
                               b1 + (X[3] - c12 * b1) / c22, b1 + b2};
    const double slip[] = {0, 0, 0.2, 0.2, 1};
    for (std::size_t i = 0; i < X.size(); ++i) {
      INFO("point " << i);
      CHECK_THAT(c.points[i].force_N, Catch::Matchers::WithinRel(expected[i], 1e-8));
      CHECK(std::abs(c.points[i].slip_area_fraction - slip[i]) < 1e-12);
    }
    CHECK(c.monotone);
  }
}

TEST_CASE("quasi-static junctions refuse overlapping discs and bad numbers", "[solve][quasi_static]") {
  QuasiStaticJunctions j;
  j.area_m2 = {1e-8, 1e-8};
  j.x_m = {0, 1e-4};  // radius 56 µm each: they overlap
  j.y_m = {0, 0};
  j.E_Pa = kE, j.shear_strength_Pa = kSigma, j.interacting = true;
  CHECK_THROWS_AS(quasi_static_junction_curve(j, {1e-6}), std::invalid_argument);
  j.interacting = false;  // independent: overlap does not matter
  CHECK_NOTHROW(quasi_static_junction_curve(j, {1e-6}));
  j.shear_strength_Pa = std::nan("");
  CHECK_THROWS_AS(quasi_static_junction_curve(j, {1e-6}), std::invalid_argument);
  j.shear_strength_Pa = kSigma;
  CHECK_THROWS_AS(quasi_static_junction_curve(j, {2e-6, 1e-6}), std::invalid_argument);
}
