// surface/tangential_contact.hpp: the FFT boundary-element tangential contact against closed forms:
// the pixel kernel against Love's rectangle and Cerruti's point force, Mindlin's stiffness of a
// circular patch, two distant patches against their point-force coupling, full sliding, and a
// sphere with Coulomb friction against Cattaneo–Mindlin (force, stick radius, tangent stiffness).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "hertz_support.hpp"
#include "physics/elastic_interaction.hpp"
#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"
#include "surface/tangential_contact.hpp"

using namespace asperity;

namespace {

constexpr double kE = 1.6e6, kNu = 0.5;      // PDMS-like
constexpr double kG = kE / (2 * (1 + kNu));  // shear modulus

TangentialContactSettings settings() {
  TangentialContactSettings s;
  s.E_Pa = kE;
  s.nu = kNu;
  s.tolerance = 1e-10;
  return s;
}

// Traction bounds σ on the pixels of discs (centres in metres from the grid's corner, radii).
struct Disc {
  double x_m, y_m, radius_m;
};
std::vector<double> disc_bounds(std::size_t n, double pixel_m, const std::vector<Disc>& discs, double sigma_Pa) {
  std::vector<double> b(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (const Disc& d : discs)
        if (std::hypot((static_cast<double>(j) + 0.5) * pixel_m - d.x_m,
                       (static_cast<double>(i) + 0.5) * pixel_m - d.y_m) < d.radius_m)
          b[i * n + j] = sigma_Pa;
  return b;
}

double area_of(const std::vector<double>& bounds, double pixel_m) {
  double count = 0;
  for (const double b : bounds) count += b > 0;
  return count * pixel_m * pixel_m;
}

}  // namespace

TEST_CASE("the pixel's Cerruti compliance: Love's rectangle at nu = 0, the point force far away, a quadrature",
          "[surface][tangential]") {
  const double h = 1e-6;
  // ν = 0: (1/πE) ∫∫ 1/r, which love_rectangle (another closed form) gives times π/E... divided by E.
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {3e-6, 0.0}, {0.7e-6, 2.1e-6}, {5e-6, -4e-6}})
    CHECK_THAT(cerruti_pixel_compliance(x, y, h, h, kE, 0.0),
               Catch::Matchers::WithinRel(love_rectangle(x, y, h, h) / kE, 1e-13));
  // Far away the pixel acts as a point force 4h² (Cerruti): the correction is O((h/r)²).
  for (const auto& [x, y] : {std::pair{60e-6, 0.0}, {0.0, 60e-6}, {40e-6, 45e-6}}) {
    const double r = std::hypot(x, y);
    const double point = 4 * h * h * cerruti_compliance(x, y, kE, kNu);
    CHECK(std::abs(cerruti_pixel_compliance(x, y, h, h, kE, kNu) / point - 1) < 2 * h * h / (r * r));
  }
  // Off the pixel, against a 2-D Gauss–Legendre rule (16 × 16 nodes per quarter) of the kernel.
  const double x = 2.5e-6, y = -1.5e-6;
  const double nodes[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                           0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  const double weights[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                             0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  double sum = 0;
  for (int qx = 0; qx < 2; ++qx)
    for (int qy = 0; qy < 2; ++qy)  // the pixel cut in four halves-by-halves squares of side h
      for (int a = 0; a < 16; ++a)
        for (int b = 0; b < 16; ++b) {
          const double ta = (a < 8 ? -nodes[a] : nodes[a - 8]), tb = (b < 8 ? -nodes[b] : nodes[b - 8]);
          const double wa = weights[a % 8], wb = weights[b % 8];
          const double sx = (qx - 0.5) * h + 0.5 * h * ta, sy = (qy - 0.5) * h + 0.5 * h * tb;
          sum += wa * wb * 0.25 * h * h * cerruti_compliance(x - sx, y - sy, kE, kNu);
        }
  CHECK_THAT(cerruti_pixel_compliance(x, y, h, h, kE, kNu), Catch::Matchers::WithinRel(sum, 1e-9));
}

TEST_CASE("a circular patch sticks with Mindlin's stiffness 8Ga/(2 - nu)", "[surface][tangential]") {
  // A flat circular patch, every pixel sticking: the rigid punch's tangential stiffness (Johnson
  // §7.2), a = √(A/π) of the pixelated disc. The error is of first order in the pixel size (the
  // punch's edge singularity on a staircase).
  double err[2];
  int k = 0;
  for (const std::size_t n : {64, 128}) {
    const double L = 1e-3, pixel = L / static_cast<double>(n);
    const auto b = disc_bounds(n, pixel, {{0.5 * L, 0.5 * L, 0.3 * L}}, 1e5);
    TangentialContact c(n, pixel, b, settings());
    const double a = std::sqrt(area_of(b, pixel) / std::numbers::pi);
    err[k++] = c.initial_stiffness_N_per_m() / (8 * kG * a / (2 - kNu)) - 1;
  }
  const double order = std::log2(err[0] / err[1]);
  INFO("k0 / Mindlin − 1 at 64² / 128²: " << err[0] << " / " << err[1] << ", order " << order);
  // Measured −6.0e-3 / −3.0e-3, order 1.00.
  CHECK(std::abs(err[0]) < 0.015);
  CHECK(std::abs(err[1]) < 0.008);
  CHECK(std::abs(order - 1) < 0.3);
}

TEST_CASE("two distant patches: independent but for Cerruti's coupling of two rigid punches", "[surface][tangential]") {
  // Two equal patches at distance d along x or y, both displaced by δ: by symmetry both carry T, and
  // δ = T/k + T c(d) with c the rigid punches' mutual compliance (disc_compliance, rigid weighting),
  // so k_pair = 2 / (1/k + c); the next correction is of relative order (kc)²(a/d)².
  const std::size_t n = 128;
  const double L = 1e-3, pixel = L / static_cast<double>(n), a = 0.08 * L;
  const auto one = disc_bounds(n, pixel, {{0.5 * L, 0.5 * L, a}}, 1e5);
  const double ae = std::sqrt(area_of(one, pixel) / std::numbers::pi);
  const double k1 = TangentialContact(n, pixel, one, settings()).initial_stiffness_N_per_m();
  for (const bool along_x : {true, false})
    for (const double d : {52 * pixel, 90 * pixel}) {  // whole pixels: each disc has the same staircase
      const double dx = along_x ? d : 0, dy = along_x ? 0 : d;
      const auto two =
          disc_bounds(n, pixel, {{0.5 * (L - dx), 0.5 * (L - dy), a}, {0.5 * (L + dx), 0.5 * (L + dy), a}}, 1e5);
      const double k2 = TangentialContact(n, pixel, two, settings()).initial_stiffness_N_per_m();
      const double c = disc_compliance(dx, dy, ae, ae, kE, kNu, TractionWeighting::rigid);
      const double coupling = 1 - k2 / (2 * k1), predicted = 1 - 1 / (1 + k1 * c);
      INFO((along_x ? "along x" : "along y")
           << ", d/a " << d / a << ": 1 − k_pair/2k = " << coupling << ", predicted " << predicted);
      // Measured: 4.5e-3 / 8.9e-4 along x, 2.8e-3 / 6.5e-4 along y (d/a 5.1 / 8.8).
      CHECK(std::abs(coupling / predicted - 1) < 0.015);
    }
}

TEST_CASE("full sliding: every pixel at its bound, Q = sigma A, from the centre's displacement under uniform traction",
          "[surface][tangential]") {
  // A uniform traction σ on a disc moves its centre by σ a (2 − ν) / (2G) (Johnson eq. 3.92
  // integrated: (σ/2πG) ∫∫ [(1 − ν) + ν cos²θ] dr dθ), the largest u_x on the disc: the slider's
  // displacement at which the last pixel starts to slip.
  const std::size_t n = 64;
  const double L = 1e-3, pixel = L / static_cast<double>(n), sigma = 2e5;
  const auto b = disc_bounds(n, pixel, {{0.5 * L, 0.5 * L, 0.3 * L}}, sigma);
  TangentialContact c(n, pixel, b, settings());
  const double a = std::sqrt(area_of(b, pixel) / std::numbers::pi);
  const double d_full = c.full_sliding_displacement_m();
  INFO("δ_full / closed form − 1 = " << d_full / (sigma * a * (2 - kNu) / (2 * kG)) - 1);
  CHECK(std::abs(d_full / (sigma * a * (2 - kNu) / (2 * kG)) - 1) < 2e-3);  // measured −4.4e-4
  const TangentialState before = c.solve(0.99 * d_full);
  const TangentialState at = c.solve(1.001 * d_full);
  CHECK(at.converged);
  CHECK(at.slipping_pixels == at.contact_pixels);
  CHECK_THAT(at.force_N, Catch::Matchers::WithinRel(sigma * area_of(b, pixel), 1e-12));
  CHECK(before.slipping_pixels < before.contact_pixels);
  CHECK(before.force_N < at.force_N);
}

namespace {

struct MindlinCase {
  double q_err = 0, c_err = 0;  // worst |Q/μP − CM| and |c/a − CM| over the points
  double k_err = 0;             // worst |dQ/dδ / (8Gc/(2 − ν)) − 1|: the stick zone is a rigid punch
};

// A smooth sphere (R 10 mm, P 1 N, E 1.6 MPa, ν 0.5) with Coulomb friction μ = 0.5, the grid
// spanning 2.6 a_Hertz: Q(δ) and the stick radius against Cattaneo–Mindlin (Johnson §7.2):
// Q/μP = 1 − (1 − δ/δ*)^(3/2), δ* = 3μP(2 − ν)/(16Ga), c = a (1 − Q/μP)^(1/3).
MindlinCase mindlin(std::size_t n) {
  const double R = 0.01, P = 1.0, Es = kE / (1 - kNu * kNu), mu = 0.5;
  const double a = testing::hertz_radius(P, R, Es);
  HeightMap m;
  const NormalContact normal = testing::hertz_contact(n, R, P, Es, 2.6, &m);
  REQUIRE(normal.converged);
  TangentialContact t(n, m.pixel_m, coulomb_bound(normal, mu), settings());
  const double d_star = 3 * mu * P * (2 - kNu) / (16 * kG * a);
  std::vector<double> deltas;
  for (const double f : {0.2, 0.4, 0.6, 0.8, 0.95}) deltas.push_back(f * d_star);
  const TangentialCurve curve = tangential_curve(t, deltas, true);
  MindlinCase out;
  for (std::size_t i = 0; i < deltas.size(); ++i) {
    const auto& p = curve.points[i];
    REQUIRE(p.converged);
    const double q = 1 - std::pow(1 - deltas[i] / d_star, 1.5);
    out.q_err = std::max(out.q_err, std::abs(p.force_N / (mu * P) - q));
    const double stick = (1 - p.slip_area_fraction) * normal.area_m2;
    out.c_err = std::max(out.c_err, std::abs(std::sqrt(stick / std::numbers::pi) / a - std::cbrt(1 - q)));
    // dQ/dδ = (3/2)(μP/δ*)(1 − δ/δ*)^(1/2) = 8Gc/(2 − ν): Mindlin's stiffness of the stick circle.
    const double k_cm = 8 * kG * a * std::cbrt(1 - q) / (2 - kNu);
    out.k_err = std::max(out.k_err, std::abs(p.tangent_stiffness_N_per_m / k_cm - 1));
  }
  CHECK(curve.monotone);
  CHECK_THAT(curve.full_sliding_force_N, Catch::Matchers::WithinRel(mu * P, 1e-10));
  return out;
}

}  // namespace

TEST_CASE("a sphere with Coulomb friction follows Cattaneo-Mindlin", "[surface][tangential]") {
  const MindlinCase c64 = mindlin(64), c128 = mindlin(128);
  const double q_order = std::log2(c64.q_err / c128.q_err), c_order = std::log2(c64.c_err / c128.c_err);
  INFO("worst |dQ/dδ / (8Gc/(2 − ν)) − 1| " << c64.k_err << " / " << c128.k_err);
  // Measured 1.2e-2 / 3.6e-3: the tangent stiffness is the stick circle's, a staircase of pixels.
  CHECK(c64.k_err < 0.03);
  CHECK(c128.k_err < 0.01);
  INFO("worst |Q/μP − CM| at 64² / 128²: " << c64.q_err << " / " << c128.q_err << " (order " << q_order
                                           << "); |c/a − CM| " << c64.c_err << " / " << c128.c_err << " (order "
                                           << c_order << ")");
  // Measured: Q 3.1e-5 / 3.2e-6, order 3.3; the stick radius (from the stick zone's pixel count, a
  // staircase) 6.6e-3 / 3.3e-3, order 1.0.
  CHECK(c64.q_err < 1e-4);
  CHECK(c128.q_err < 1e-5);
  CHECK(q_order > 2.5);
  CHECK(c128.c_err < 0.007);
  CHECK(std::abs(c_order - 1) < 0.3);
}
