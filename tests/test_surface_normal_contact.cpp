// surface/normal_contact.hpp: the FFT boundary-element contact against Hertz (sphere on a flat),
// Love's rectangle against its point-force limit, and the load balance.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"

using namespace asperity;

namespace {

struct HertzCase {
  double a_num, a_hertz, p0_num, p0_hertz, d_num, d_hertz, load_balance;
  int iterations;
};

// A smooth sphere R = 10 mm pressed with P = 1 N into E* = 2.13 MPa (PDMS-like): Hertz gives
// a = (3PR/4E*)^(1/3) ≈ 1.52 mm. The grid spans 2.6 a.
HertzCase hertz(std::size_t n) {
  const double R = 0.01, P = 1.0, Es = 2.13e6;
  const double a = std::cbrt(3 * P * R / (4 * Es));
  HeightMap m;
  m.n = n;
  m.pixel_m = 2.6 * a / static_cast<double>(n);
  m.h_m.assign(n * n, 0.0);
  add_sphere(m, R);
  NormalContactSettings s;
  s.E_star_Pa = Es;
  s.load_N = P;
  s.tolerance = 1e-12;
  const NormalContact c = solve_normal_contact(m, s);
  REQUIRE(c.converged);
  double total = 0, pmax = 0;
  for (const double p : c.pressure_Pa) total += p * m.pixel_m * m.pixel_m, pmax = std::max(pmax, p);
  return {std::sqrt(c.area_m2 / std::numbers::pi), a, pmax, 3 * P / (2 * std::numbers::pi * a * a), c.approach_m, a * a / R,
          std::abs(total - P) / P, c.iterations};
}

}  // namespace

TEST_CASE("Love's rectangle tends to the point force far away", "[surface][contact]") {
  // Far from a pixel of side 2h the uniform load acts as a point force: u E* = (4h²)/(π r).
  const double h = 1e-6;
  for (const double r : {50e-6, 200e-6}) {
    const double exact = love_rectangle(r, 0, h, h), point = 4 * h * h / (std::numbers::pi * r);
    CHECK(std::abs(exact / point - 1) < 3 * (h * h) / (r * r));  // the quadrupole correction is O((h/r)²)
  }
  // At the centre of a square of side 2h: u E* = (8h/π) ln(1 + √2) ≈ 2.24 h (Johnson §3.4).
  CHECK_THAT(love_rectangle(0, 0, h, h), Catch::Matchers::WithinRel(8 * h / std::numbers::pi * std::log(1 + std::sqrt(2.0)), 1e-14));
}

TEST_CASE("a sphere on a flat gives Hertz's contact radius, central pressure and approach", "[surface][contact]") {
  const HertzCase c64 = hertz(64), c128 = hertz(128), c256 = hertz(256);
  for (const HertzCase& c : {c64, c128, c256}) CHECK(c.load_balance < 1e-12);
  const double ea[] = {std::abs(c64.a_num / c64.a_hertz - 1), std::abs(c128.a_num / c128.a_hertz - 1),
                       std::abs(c256.a_num / c256.a_hertz - 1)};
  const double ep = std::abs(c256.p0_num / c256.p0_hertz - 1), ed = std::abs(c256.d_num / c256.d_hertz - 1);
  const double ep64 = std::abs(c64.p0_num / c64.p0_hertz - 1), ep128 = std::abs(c128.p0_num / c128.p0_hertz - 1);
  const double ed64 = std::abs(c64.d_num / c64.d_hertz - 1), ed128 = std::abs(c128.d_num / c128.d_hertz - 1);
  INFO("Hertz at 64/128/256: radius error " << ea[0] << " / " << ea[1] << " / " << ea[2] << "; p0 " << ep64 << " / "
       << ep128 << " / " << ep << "; approach " << ed64 << " / " << ed128 << " / " << ed << "; iterations "
       << c64.iterations << " / " << c128.iterations << " / " << c256.iterations);
  // Measured: radius (from the contact area: a staircase of pixels) 3.3e-3 / 9.1e-4 / 1.2e-3;
  // central pressure 3.3e-4 / 8.6e-5 / 2.1e-5 and approach 4.7e-4 / 1.2e-4 / 2.9e-5, both of
  // second order in the pixel size (1.92, 2.05 and 1.95, 2.04 per halving).
  CHECK(ea[2] < 0.005);
  CHECK(ep < 1e-4);
  CHECK(ed < 1.5e-4);
  for (const double order : {std::log2(ep64 / ep128), std::log2(ep128 / ep), std::log2(ed64 / ed128), std::log2(ed128 / ed)})
    CHECK(std::abs(order - 2) < 0.2);
}
