// solve/interacting/fft_coupling.hpp: the precorrected-FFT product y = C x of the junctions'
// coupling, against the dense product of the same kernel (physics/elastic_interaction.hpp,
// evaluated pair by pair: the second method).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

#include "physics/elastic_interaction.hpp"
#include "scene/load.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/fft_coupling.hpp"
#include "solve/interacting/interaction_matrix.hpp"

namespace {

using asperity::FftCoupling;
using asperity::FftCouplingSettings;
using asperity::TractionWeighting;

constexpr double kE = 1.6e6, kNu = 0.5;  // the stand-ins' PDMS

// n junctions on a jittered square lattice of spacing 0.23 mm (the stand-ins' density) cut to a
// disc, radii 8–40 µm, never overlapping.
struct Population {
  std::vector<double> x, y, a;
};
Population population(std::size_t n, unsigned seed, double spacing = 2.3e-4) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3, 0.3), r(8e-6, 4e-5);
  Population p;
  const int side = static_cast<int>(std::ceil(std::sqrt(4.0 * n / M_PI))) + 2;
  for (int i = -side; i <= side && p.x.size() < n; ++i)
    for (int j = -side; j <= side && p.x.size() < n; ++j) {
      if (std::hypot(i, j) > side / 2.0 + 0.5) continue;
      p.x.push_back((i + u(rng)) * spacing);
      p.y.push_back((j + u(rng)) * spacing);
      p.a.push_back(r(rng));
    }
  return p;
}

std::vector<double> dense_product(const Population& p, const std::vector<double>& f, TractionWeighting w) {
  const std::size_t n = p.x.size();
  std::vector<double> y(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j)
        y[i] += asperity::disc_compliance(p.x[i] - p.x[j], p.y[i] - p.y[j], p.a[i], p.a[j], kE, kNu, w) * f[j];
  return y;
}

std::vector<double> forces(std::size_t n, unsigned seed) {  // positive, as the junctions' loads are
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  std::vector<double> f(n);
  for (auto& v : f) v = u(rng);
  return f;
}

// max_i |ỹ_i − y_i| / max_i |y_i|
double error(const FftCoupling& c, const std::vector<double>& f, const std::vector<double>& exact) {
  std::vector<double> y(f.size());
  c.apply(f.data(), y.data());
  double e = 0, s = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    e = std::max(e, std::abs(y[i] - exact[i])), s = std::max(s, std::abs(exact[i]));
  return e / s;
}

}  // namespace

TEST_CASE("FFT coupling: the product converges to the dense one as the exact near radius grows",
          "[solve][fft_coupling]") {
  // Error ∝ (h/R)^p in the far field: order 8 on a grid of half the junction spacing. Measured
  // (uniform; rigid within 3 %): near 8 cells 8.9e-8, 12: 3.3e-9, 16: 3.9e-10, 24: 1.6e-11, an
  // observed order of 7.5-8.1 in R, the stencil's 8.
  for (const auto w : {TractionWeighting::uniform, TractionWeighting::rigid}) {
    const Population p = population(900, 7);
    const auto f = forces(p.x.size(), 11);
    const auto exact = dense_product(p, f, w);
    std::vector<double> errors;
    const std::vector<double> radii{8.0, 12.0, 16.0, 24.0};
    for (double near : radii) {
      FftCouplingSettings s;
      s.order = 8, s.cell_per_spacing = 0.5, s.near_cells = near;
      const FftCoupling c(p.x, p.y, p.a, kE, kNu, w, s);
      errors.push_back(error(c, f, exact));
    }
    for (std::size_t k = 1; k < errors.size(); ++k) {
      const double order = std::log(errors[k - 1] / errors[k]) / std::log(radii[k] / radii[k - 1]);
      INFO("weighting " << int(w) << ", near " << radii[k] << ": observed order " << order);
      CHECK(order > 6.5);
      CHECK(order < 9.5);
    }
    CHECK(errors.back() < 5e-11);
  }
}

TEST_CASE("FFT coupling: a finer grid at the same exact radius, and a higher order, are more accurate",
          "[solve][fft_coupling]") {
  const Population p = population(900, 7);
  const auto f = forces(p.x.size(), 11);
  const auto exact = dense_product(p, f, TractionWeighting::uniform);
  const auto run = [&](int order, double cell, double radius_spacings) {
    FftCouplingSettings s;
    s.order = order, s.cell_per_spacing = cell, s.near_cells = radius_spacings / cell;
    return error(FftCoupling(p.x, p.y, p.a, kE, kNu, TractionWeighting::uniform, s), f, exact);
  };
  // At 6 spacings: cell 1 → 0.5 → 0.25 at order 6 (2^6 = 64 expected; measured 3.4e-6, 4.7e-8,
  // 5.6e-10: 73 and 83), and order 4 → 6 → 8 at cell 0.5 (1.9e-6, 4.7e-8, 3.3e-9: 41 and 14).
  const double c1 = run(6, 1.0, 6), c2 = run(6, 0.5, 6), c4 = run(6, 0.25, 6);
  INFO("cell 1, 0.5, 0.25: " << c1 << ", " << c2 << ", " << c4);
  CHECK(c2 < c1 / 25);
  CHECK(c4 < c2 / 25);
  const double o4 = run(4, 0.5, 6), o8 = run(8, 0.5, 6);
  INFO("order 4, 8: " << o4 << ", " << o8);
  CHECK(c2 < o4 / 12);
  CHECK(o8 < c2 / 5);
}

TEST_CASE("FFT coupling: every pair within the exact radius, or clusters far apart, change nothing",
          "[solve][fft_coupling]") {
  // All pairs near: the grid's own values cancel exactly (up to the FFT's rounding).
  const Population p = population(150, 3);
  const auto f = forces(p.x.size(), 5);
  const auto exact = dense_product(p, f, TractionWeighting::uniform);
  FftCouplingSettings s;
  s.near_cells = 64;
  const FftCoupling all(p.x, p.y, p.a, kE, kNu, TractionWeighting::uniform, s);
  CHECK(all.near_pairs() == p.x.size() * (p.x.size() - 1) / 2);
  CHECK(error(all, f, exact) < 1e-14);  // measured 1.5e-15
  // Two such clusters 10 km apart: the grid coarsens to keep its size, each cluster within the
  // exact radius, and the clusters' coupling (10⁶ times weaker) interpolated at (h/d)^p.
  Population two = p;
  for (std::size_t i = 0; i < p.x.size(); ++i)
    two.x.push_back(p.x[i] + 1e4), two.y.push_back(p.y[i]), two.a.push_back(p.a[i]);
  const auto f2 = forces(two.x.size(), 6);
  const auto exact2 = dense_product(two, f2, TractionWeighting::uniform);
  const FftCoupling far(two.x, two.y, two.a, kE, kNu, TractionWeighting::uniform);
  CHECK(far.grid_points() <= 2048u * 2048u);
  CHECK(error(far, f2, exact2) < 1e-14);  // measured 1.8e-15
}

TEST_CASE("FFT coupling: the product is symmetric, as C is", "[solve][fft_coupling]") {
  const Population p = population(600, 9);
  const auto u = forces(p.x.size(), 1), v = forces(p.x.size(), 2);
  const FftCoupling c(p.x, p.y, p.a, kE, kNu, TractionWeighting::uniform);
  std::vector<double> cu(u.size()), cv(v.size());
  c.apply(u.data(), cu.data());
  c.apply(v.data(), cv.data());
  double vcu = 0, ucv = 0;
  for (std::size_t i = 0; i < u.size(); ++i) vcu += v[i] * cu[i], ucv += u[i] * cv[i];
  CHECK(std::abs(vcu - ucv) < 2e-15 * std::abs(vcu));  // measured 2.6e-16
}

TEST_CASE("FFT coupling: impossible settings are refused", "[solve][fft_coupling]") {
  const Population p = population(20, 1);
  for (const FftCouplingSettings s :
       {FftCouplingSettings{5, 8, 0.5}, FftCouplingSettings{14, 8, 0.5}, FftCouplingSettings{8, 0.5, 0.5},
        FftCouplingSettings{8, 8, 0}, FftCouplingSettings{8, std::nan(""), 0.5}})
    CHECK_THROWS_AS(FftCoupling(p.x, p.y, p.a, kE, kNu, TractionWeighting::uniform, s), std::invalid_argument);
  CHECK_THROWS_AS(FftCoupling(p.x, p.y, std::vector<double>(3, 1e-5), kE, kNu, TractionWeighting::uniform),
                  std::invalid_argument);
}

TEST_CASE("FFT coupling: a stand-in's junctions at the defaults, against the solver's dense C",
          "[solve][fft_coupling]") {
  // The stand-in P4.00N (STAND-IN data): 1,201 junctions, radii 18-181 µm, its closest pairs
  // 8e-8 m apart. Measured at the defaults: 3.9e-9 (results/bench/fft_coupling.csv).
  const asperity::Scene scene = asperity::load_scene(
      std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P4.00N.yaml", {"model.interactions=elastic"});
  const asperity::Problem problem = asperity::make_problem(scene);
  const asperity::InteractionMatrix C = asperity::interaction_matrix(problem);
  const std::size_t n = problem.size();
  const auto f = forces(n, 3);
  std::vector<double> exact(n, 0.0), y(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) exact[i] += C(i, j) * f[j];
  const FftCoupling fast(problem);
  CHECK(error(fast, f, exact) < 1.5e-8);
  // A cut-off kernel is not translation invariant: refused.
  const asperity::Scene cut =
      asperity::load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P4.00N.yaml",
                           {"model.interactions=elastic", "model.interaction_cutoff=5e-4"});
  CHECK_THROWS_AS(FftCoupling(asperity::make_problem(cut)), std::invalid_argument);
}
