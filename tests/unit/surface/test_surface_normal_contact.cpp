// surface/normal_contact.hpp: the FFT boundary-element contact against Hertz (sphere on a flat),
// Love's rectangle against its point-force limit, and the load balance.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "hertz_support.hpp"
#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"
#include "surface/self_affine.hpp"

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
  const double a = testing::hertz_radius(P, R, Es);
  HeightMap m;
  const NormalContact c = testing::hertz_contact(n, R, P, Es, 2.6, &m);
  REQUIRE(c.converged);
  double total = 0, pmax = 0;
  for (const double p : c.pressure_Pa) total += p * m.pixel_m * m.pixel_m, pmax = std::max(pmax, p);
  return {std::sqrt(c.area_m2 / std::numbers::pi),
          a,
          pmax,
          3 * P / (2 * std::numbers::pi * a * a),
          c.approach_m,
          a * a / R,
          std::abs(total - P) / P,
          c.iterations};
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
  CHECK_THAT(love_rectangle(0, 0, h, h),
             Catch::Matchers::WithinRel(8 * h / std::numbers::pi * std::log(1 + std::sqrt(2.0)), 1e-14));
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
                                            << ep128 << " / " << ep << "; approach " << ed64 << " / " << ed128 << " / "
                                            << ed << "; iterations " << c64.iterations << " / " << c128.iterations
                                            << " / " << c256.iterations);
  // Measured: radius (from the contact area: a staircase of pixels) 3.3e-3 / 9.1e-4 / 1.2e-3;
  // central pressure 3.3e-4 / 8.6e-5 / 2.1e-5 and approach 4.7e-4 / 1.2e-4 / 2.9e-5, both of
  // second order in the pixel size (1.92, 2.05 and 1.95, 2.04 per halving).
  CHECK(ea[2] < 0.005);
  CHECK(ep < 1e-4);
  CHECK(ed < 1.5e-4);
  for (const double order :
       {std::log2(ep64 / ep128), std::log2(ep128 / ep), std::log2(ed64 / ed128), std::log2(ed128 / ed)})
    CHECK(std::abs(order - 2) < 0.2);
}

TEST_CASE("periodic: a wavy surface gives Westergaard's pressure in full contact and contact width in partial",
          "[surface][contact]") {
  // h = Δ cos(2πx/λ), λ = L (Johnson, Contact Mechanics §13.2): full contact needs p̄ ≥ p* = π E* Δ / λ,
  // then p = p̄ + p* cos(2πx/λ); below it the contact half-width a obeys sin²(πa/λ) = p̄ / p*.
  const std::size_t n = 256;
  const double L = 1e-3, D = 1e-6, Es = 2e6, pstar = std::numbers::pi * Es * D / L;
  HeightMap m;
  m.n = n;
  m.pixel_m = L / static_cast<double>(n);
  m.h_m.resize(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      m.h_m[i * n + j] = D * std::cos(2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n));
  NormalContactSettings s;
  s.E_star_Pa = Es;
  s.periodic = true;
  s.tolerance = 1e-12;
  s.load_N = 2 * pstar * L * L;  // p̄ = 2 p*
  const NormalContact full = solve_normal_contact(m, s);
  REQUIRE(full.converged);
  double worst = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double exact =
        2 * pstar + pstar * std::cos(2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n));
    worst = std::max(worst, std::abs(full.pressure_Pa[j] - exact) / pstar);
  }
  INFO("full contact: worst pressure error " << worst << " p*, " << full.iterations << " iterations");
  CHECK(worst < 1e-10);  // one Fourier mode: the spectral kernel is exact (measured 1.5e-11)
  CHECK(std::abs(full.area_m2 / (L * L) - 1) < 1e-12);
  for (const double ratio : {0.1, 0.5}) {
    s.load_N = ratio * pstar * L * L;
    const NormalContact part = solve_normal_contact(m, s);
    REQUIRE(part.converged);
    const double width = part.area_m2 / (L * L), exact = 2 * std::asin(std::sqrt(ratio)) / std::numbers::pi;
    INFO("p/p* " << ratio << ": contact fraction " << width << " vs " << exact);
    CHECK(std::abs(width - exact) < 2.0 / static_cast<double>(n));  // within two pixels of the edge
  }
}

TEST_CASE("self-affine surfaces at small loads: contact area linear in load, kappa in the published range",
          "[surface][contact][heavy]") {
  // A/A0 = κ p̄ / (E* h'_rms) at small loads; simulations give κ ≈ 2–2.5 depending on H and on how
  // well the shortest wavelength is resolved (Hyun, Pei, Molinari & Robbins, PRE 70, 026117,
  // 2004; Müser et al., Tribol. Lett. 65, 118, 2017: κ ≈ 2 in the continuum limit), above
  // Persson's √(8/π) ≈ 1.6. Measured here (seed 7, λ_r = L/4, h'_rms = 0.1 from central
  // differences): κ = 2.62 / 2.55 (H 0.3) and 2.58 / 2.50 (H 0.8) at 256², λ_s = 4 px, and
  // 2.46 / 2.44 and 2.42 / 2.30 at 512², λ_s = 8 px, for p̄/(E* h') = 0.005 / 0.01.
  for (const double H : {0.3, 0.8}) {
    double kappa_fine[2] = {}, kappa_coarse = 0;
    for (const std::size_t n : {256, 512}) {
      SelfAffineSpec s;
      s.n = n;
      s.length_m = 1e-3;
      s.hurst = H;
      s.rolloff_wavelength_m = s.length_m / 4;
      s.short_wavelength_m = (n == 256 ? 4.0 : 8.0) * s.length_m / static_cast<double>(n);
      s.rms_slope = 0.1;
      s.seed = 7;
      const HeightMap m = self_affine_surface(s);
      for (int k = 0; k < 2; ++k) {
        const double load = (k == 0 ? 0.005 : 0.01);
        NormalContactSettings c;
        c.E_star_Pa = 1e6;
        c.periodic = true;
        c.tolerance = 1e-8;
        c.load_N = load * c.E_star_Pa * 0.1 * s.length_m * s.length_m;
        const NormalContact r = solve_normal_contact(m, c);
        REQUIRE(r.converged);
        const double kappa = r.area_m2 / (s.length_m * s.length_m) / load;
        if (n == 512)
          kappa_fine[k] = kappa;
        else if (k == 1)
          kappa_coarse = kappa;
      }
    }
    INFO("H " << H << ": kappa " << kappa_fine[0] << " / " << kappa_fine[1] << " at 512^2; " << kappa_coarse
              << " at 256^2");
    for (const double k : kappa_fine) CHECK((k > 1.8 && k < 2.6));
    CHECK(std::abs(kappa_fine[1] / kappa_fine[0] - 1) < 0.1);  // linear: κ changes little as the load doubles
    CHECK(kappa_fine[1] < kappa_coarse);                       // and falls as λ_s is better resolved
  }
}
