// Junction-area distributions of the stand-in generator: inverse CDFs against closed forms,
// sampling statistics, seeds.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "generate/distributions.hpp"

using namespace asperity;

namespace {

const std::vector<double> kUs{1e-9, 1e-6, 1e-3, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999, 1 - 1e-6, 1 - 1e-9};

// Closed-form mean of p(a) ∝ a^(−τ) on [lo, hi], written independently of PowerLaw::moment.
double power_law_mean(double tau, double lo, double hi) {
  if (tau == 1.0) return (hi - lo) / std::log(hi / lo);
  if (tau == 2.0) return std::log(hi / lo) / (1.0 / lo - 1.0 / hi);
  const double s = 1.0 - tau;
  return s / (s + 1.0) * (std::pow(hi, s + 1) - std::pow(lo, s + 1)) / (std::pow(hi, s) - std::pow(lo, s));
}

double power_law_second_moment(double tau, double lo, double hi) {
  if (tau == 1.0) return (hi * hi - lo * lo) / (2.0 * std::log(hi / lo));
  if (tau == 2.0) return (hi - lo) / (1.0 / lo - 1.0 / hi);
  const double s = 1.0 - tau;
  return s / (s + 2.0) * (std::pow(hi, s + 2) - std::pow(lo, s + 2)) / (std::pow(hi, s) - std::pow(lo, s));
}

}  // namespace

TEST_CASE("Uniform01 gives doubles strictly inside (0, 1) from mt19937_64's top 53 bits", "[generate]") {
  io::Uniform01 u(42);
  std::mt19937_64 g(42);
  for (int i = 0; i < 1000; ++i) {
    const double x = u();
    REQUIRE(x > 0.0);
    REQUIRE(x < 1.0);
    REQUIRE(x == (static_cast<double>(g() >> 11) + 0.5) / 9007199254740992.0);
  }
  // The standard fixes mt19937_64's sequence: its 10000th output from the default seed.
  std::mt19937_64 d;
  d.discard(9999);
  CHECK(d() == 9981545732273789042ULL);
}

TEST_CASE("power-law quantile inverts its CDF and matches the closed forms", "[generate]") {
  for (double tau : {0.5, 1.0, 1.2, 1.5, 2.0, 3.0}) {
    const PowerLaw d{tau, 1e-9, 1e-7};
    for (double u : kUs) {
      const double a = d.quantile(u);
      INFO("tau = " << tau << ", u = " << u);
      REQUIRE(a >= d.a_min);
      REQUIRE(a <= d.a_max);
      CHECK(std::abs(d.cdf(a) - u) < 1e-12);
      // Closed forms of the inverse CDF.
      double expect;
      if (tau == 1.0)
        expect = d.a_min * std::pow(d.a_max / d.a_min, u);
      else if (tau == 2.0)
        expect = 1.0 / (1.0 / d.a_min - u * (1.0 / d.a_min - 1.0 / d.a_max));
      else {
        const double s = 1.0 - tau;
        expect = std::pow(std::pow(d.a_min, s) + u * (std::pow(d.a_max, s) - std::pow(d.a_min, s)), 1.0 / s);
      }
      CHECK(a == Approx(expect).epsilon(1e-12));
    }
    CHECK(d.mean() == Approx(power_law_mean(tau, d.a_min, d.a_max)).epsilon(1e-12));
  }
}

TEST_CASE("power-law sample mean agrees with the closed-form mean within its standard error", "[generate]") {
  for (double tau : {1.0, 1.5, 2.0}) {
    const PowerLaw d{tau, 1e-9, 1e-7};
    const std::size_t n = 200000;
    const JunctionPopulation pop = draw_population(Distribution{d}, n, 7 + static_cast<std::uint64_t>(10 * tau));
    double sum = 0;
    for (double a : pop.area_m2) sum += a;
    const double mean = sum / static_cast<double>(n);
    const double m1 = power_law_mean(tau, d.a_min, d.a_max);
    const double sd = std::sqrt(power_law_second_moment(tau, d.a_min, d.a_max) - m1 * m1);
    INFO("tau = " << tau << ", sample mean " << mean << ", closed form " << m1);
    CHECK(std::abs(mean - m1) < 5.0 * sd / std::sqrt(static_cast<double>(n)));
  }
}

TEST_CASE("lognormal quantile: median, one sigma, truncation, CDF round trip", "[generate]") {
  const LogNormal d{1e-8, 0.6};
  CHECK(d.quantile(0.5) == Approx(1e-8).epsilon(1e-14));
  CHECK(d.quantile(io::normal_cdf(1.0)) == Approx(1e-8 * std::exp(0.6)).epsilon(1e-12));
  CHECK(d.quantile(io::normal_cdf(-2.0)) == Approx(1e-8 * std::exp(-1.2)).epsilon(1e-12));
  for (double u : kUs) CHECK(std::abs(d.cdf(d.quantile(u)) - u) < 1e-12);

  const LogNormal t{1e-8, 1.0, 2e-9, 5e-8};
  for (double u : kUs) {
    const double a = t.quantile(u);
    INFO("u = " << u);
    REQUIRE(a >= t.a_min);
    REQUIRE(a <= t.a_max);
    CHECK(std::abs(t.cdf(a) - u) < 1e-12);
  }
  CHECK(t.cdf(t.a_min) == 0.0);
  CHECK(t.cdf(t.a_max) == 1.0);
}

TEST_CASE("mixture: component weights are recovered within binomial error bars", "[generate]") {
  Mixture m;
  m.weights = {2.0, 5.0, 3.0};  // normalised on use: 0.2, 0.5, 0.3
  m.components = {Fixed{1e-9}, PowerLaw{1.5, 2e-9, 1e-8}, LogNormal{5e-8, 0.3, 2e-8, 1e-7}};
  const Distribution d{m};
  const std::size_t n = 100000;
  const JunctionPopulation pop = draw_population(d, n, 2024);
  std::size_t c0 = 0, c1 = 0, c2 = 0;
  for (double a : pop.area_m2) {
    if (a == 1e-9)
      ++c0;
    else if (a >= 2e-9 && a <= 1e-8)
      ++c1;
    else if (a >= 2e-8 && a <= 1e-7)
      ++c2;
  }
  REQUIRE(c0 + c1 + c2 == n);  // supports are disjoint: every draw is attributed
  const double counts[3] = {double(c0), double(c1), double(c2)};
  for (int j = 0; j < 3; ++j) {
    const double w = m.weight(static_cast<std::size_t>(j));
    const double se = std::sqrt(w * (1 - w) / static_cast<double>(n));
    INFO("component " << j << ": " << counts[j] / n << " vs " << w);
    CHECK(std::abs(counts[j] / static_cast<double>(n) - w) < 5.0 * se);
  }
  // pick() follows the cumulative weights.
  CHECK(m.pick(0.1999) == 0);
  CHECK(m.pick(0.2001) == 1);
  CHECK(m.pick(0.6999) == 1);
  CHECK(m.pick(0.7001) == 2);
  // The mixture CDF is the weighted sum.
  CHECK(d.cdf(1e-9) == Approx(0.2));
  CHECK(d.cdf(1.5e-8) == Approx(0.7));
}

TEST_CASE("draw_population: same seed same areas, new seed new areas, positions optional", "[generate]") {
  const Distribution d{PowerLaw{1.5, 1e-9, 1e-7}};
  const auto a = draw_population(d, 500, 1);
  const auto b = draw_population(d, 500, 1);
  const auto c = draw_population(d, 500, 2);
  CHECK(a.area_m2 == b.area_m2);
  CHECK(a.area_m2 != c.area_m2);
  CHECK(a.x_m.empty());
  CHECK(a.y_m.empty());
  const auto p = draw_population(d, 500, 1, 0.01);
  CHECK(p.area_m2 == a.area_m2);  // positions come after the areas in the stream
  REQUIRE(p.x_m.size() == 500);
  REQUIRE(p.y_m.size() == 500);
  for (std::size_t i = 0; i < 500; ++i) {
    CHECK((p.x_m[i] > 0 && p.x_m[i] < 0.01));
    CHECK((p.y_m[i] > 0 && p.y_m[i] < 0.01));
  }
}

TEST_CASE("invalid distribution parameters are rejected", "[generate]") {
  CHECK_THROWS_AS(draw_population(Distribution{PowerLaw{1.5, 1e-7, 1e-9}}, 1, 1), std::invalid_argument);
  CHECK_THROWS_AS(draw_population(Distribution{LogNormal{1e-8, -1}}, 1, 1), std::invalid_argument);
  CHECK_THROWS_AS(draw_population(Distribution{Fixed{0}}, 1, 1), std::invalid_argument);
  Mixture m;
  m.weights = {1.0};
  CHECK_THROWS_AS(draw_population(Distribution{m}, 1, 1), std::invalid_argument);
}
