// physics/elastic_interaction.hpp: Cerruti's point compliance and its average over two discs,
// against a direct numerical integration of the point kernel over two uniformly loaded discs.
#include <boost/math/quadrature/gauss.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "physics/elastic_interaction.hpp"

using namespace asperity;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kE = 1.6e6, kNu = 0.5;

// Radial nodes r/R on [0, 1] and weights summing to one, ±abscissa of 40-point Gauss–Legendre:
//  - uniform traction: in s = r²/R² (area-uniform), r/R = sqrt(s);
//  - the rigid punch's traction 1/(2πR sqrt(R² − r²)): with r = R sin φ its measure is
//    sin φ dφ dθ / 2π, smooth in φ ∈ [0, π/2].
void radial_nodes(bool rigid, std::vector<double>& rho, std::vector<double>& wr) {
  using G = boost::math::quadrature::gauss<double, 40>;
  const auto& x = G::abscissa();
  const auto& w = G::weights();
  for (std::size_t k = 0; k < x.size(); ++k)
    for (const double sign : {-1.0, 1.0}) {
      if (k == 0 && sign > 0 && x[0] == 0.0) continue;
      if (rigid) {
        const double phi = 0.25 * M_PI * (1 + sign * x[k]);
        rho.push_back(std::sin(phi));
        wr.push_back(0.25 * M_PI * w[k] * std::sin(phi));
      } else {
        rho.push_back(std::sqrt(0.5 * (1 + sign * x[k])));
        wr.push_back(0.5 * w[k]);
      }
    }
}

// ∫∫ K(x_i − x_j) over disc i (radius a, centre d) and disc j (radius b, centre 0), each
// weighted by its traction (uniform or the rigid punch's) normalised to a unit total: the radial
// nodes above × midpoint in θ. Exact for smooth integrands as the nodes grow; the kernel is smooth
// for separated discs. Independent of the series and of its moments.
double direct_average(double dx, double dy, double a, double b, int n_theta, bool rigid) {
  std::vector<double> rho, wr;
  radial_nodes(rigid, rho, wr);
  std::vector<double> px, py, pw;
  for (std::size_t k = 0; k < rho.size(); ++k)
    for (int t = 0; t < n_theta; ++t) {
      const double th = (t + 0.5) * 2 * M_PI / n_theta;
      px.push_back(rho[k] * std::cos(th));
      py.push_back(rho[k] * std::sin(th));
      pw.push_back(wr[k] / n_theta);
    }
  double sum = 0;
  for (std::size_t i = 0; i < px.size(); ++i)
    for (std::size_t j = 0; j < px.size(); ++j)
      sum += pw[i] * pw[j] * cerruti_compliance(dx + a * px[i] - b * px[j], dy + a * py[i] - b * py[j], kE, kNu);
  return sum;
}
double direct_disc_average(double dx, double dy, double a, double b, int n_theta) {
  return direct_average(dx, dy, a, b, n_theta, false);
}
double direct_rigid_average(double dx, double dy, double a, double b, int n_theta) {
  return direct_average(dx, dy, a, b, n_theta, true);
}

}  // namespace

TEST_CASE("Cerruti's point compliance: its closed form and its symmetries", "[physics][interaction]") {
  const double c = (1 + kNu) / (2 * M_PI * kE);
  // Along x: (1+ν)/(2πE)·2/r; along y: (1+ν)/(2πE)·2(1−ν)/r (Johnson eq. 3.86a).
  CHECK_THAT(cerruti_compliance(1e-3, 0, kE, kNu), WithinRel(c * 2 / 1e-3, 1e-15));
  CHECK_THAT(cerruti_compliance(0, 1e-3, kE, kNu), WithinRel(c * 2 * (1 - kNu) / 1e-3, 1e-15));
  CHECK(cerruti_compliance(-3e-4, 2e-4, kE, kNu) == cerruti_compliance(3e-4, -2e-4, kE, kNu));
}

TEST_CASE("the disc-averaged compliance equals a direct integration over two uniformly loaded discs",
          "[physics][interaction]") {
  struct Case {
    double dx, dy, a, b, tol;
    int n_theta = 48;
  };
  // Separated discs: both agree to ~1e-13 (measured ≤ 1.6e-13 at gap ≥ a, ≤ 8e-13 at gap 0.2a);
  // touching discs (gap 0) are nearly singular at the contact point, where the quadrature's
  // 80 × 160 nodes per disc (80 × 96 at gap ≤ 0.4a, 80 × 48 elsewhere) leave ~1e-5 (measured 8.8e-6 and 1.9e-6).
  const Case cases[] = {
      {3e-5, 0, 1e-5, 1e-5, 5e-13},       {0, 3e-5, 1e-5, 1e-5, 5e-13},
      {2e-5, 2e-5, 1e-5, 5e-6, 5e-13},    {1.8e-5, 0.6e-5, 1e-5, 0.4e-5, 3e-12, 96},
      {2.4e-5, 0, 1e-5, 1e-5, 3e-12, 96}, {0, 2.2e-5, 1e-5, 1e-5, 3e-12, 96},
      {2e-5, 0, 1e-5, 1e-5, 3e-5, 160},   {0, 2e-5, 1e-5, 1e-5, 3e-5, 160},
  };
  for (const Case& k : cases) {
    const double direct = direct_disc_average(k.dx, k.dy, k.a, k.b, k.n_theta);
    INFO("dx " << k.dx << " dy " << k.dy << " a " << k.a << " b " << k.b);
    CHECK_THAT(disc_compliance(k.dx, k.dy, k.a, k.b, kE, kNu), WithinRel(direct, k.tol));
  }
}

TEST_CASE("the disc average is symmetric and tends to the point kernel for small or distant discs",
          "[physics][interaction]") {
  // Betti: swapping the discs (and the sign of the offset) changes nothing.
  CHECK_THAT(disc_compliance(3e-5, 1e-5, 1e-5, 4e-6, kE, kNu),
             WithinRel(disc_compliance(-3e-5, -1e-5, 4e-6, 1e-5, kE, kNu), 1e-15));
  // Near-touching unequal discs (radii 7.4 apart, a gap of 6e-4 of their sum, as the stand-ins'
  // closest pairs): the series needs ~2,000 terms, and computed from the smaller radius its
  // moments underflowed, so the two orders differed by 9e-7 along x and 2e-6 along y.
  for (const double angle : {0.0, 1.0, M_PI / 2}) {
    const double ra = 1.89e-5, rb = 1.39e-4, gap = 9.15e-8, dd = ra + rb + gap;
    const double ex = dd * std::cos(angle), ey = dd * std::sin(angle);
    CHECK_THAT(disc_compliance(ex, ey, ra, rb, kE, kNu), WithinRel(disc_compliance(-ex, -ey, rb, ra, kE, kNu), 1e-15));
    CHECK_THAT(disc_compliance(ex, ey, ra, rb, kE, kNu, TractionWeighting::rigid),
               WithinRel(disc_compliance(-ex, -ey, rb, ra, kE, kNu, TractionWeighting::rigid), 1e-15));
    // The series sees the radii only as the smaller and the larger: symmetric bit for bit, and
    // given the distance it is the same value.
    for (const TractionWeighting w : {TractionWeighting::uniform, TractionWeighting::rigid}) {
      const double c = disc_compliance(ex, ey, ra, rb, kE, kNu, w);
      CHECK(c == disc_compliance(-ex, -ey, rb, ra, kE, kNu, w));
      CHECK(c == disc_compliance_at_distance(ex, ey, std::hypot(ex, ey), ra, rb, kE, kNu, w));
    }
  }
  // Point discs: exactly the point form.
  CHECK_THAT(disc_compliance(3e-5, 1e-5, 0, 0, kE, kNu), WithinRel(cerruti_compliance(3e-5, 1e-5, kE, kNu), 1e-15));
  // Far apart: the first correction is (a² + b²)/8 · ∇²K, relative O((a/d)²) = 1e-6; the next
  // is O((a/d)⁴) = 1e-12 (measured 7.8e-14).
  const double d = 1e-2, a = 1e-5;
  const double point = cerruti_compliance(d, 0, kE, kNu);
  const double c = (1 + kNu) / (2 * M_PI * kE);
  const double lap = c * ((2 - kNu) / (d * d * d) - 3 * kNu / (d * d * d));  // ∇² of (2−ν)/r + ν cos2θ/r
  CHECK_THAT(disc_compliance(d, 0, a, a, kE, kNu), WithinRel(point + 2 * a * a / 8 * lap, 3e-13));
  // Overlapping discs are refused.
  CHECK_THROWS_AS(disc_compliance(1.5e-5, 0, 1e-5, 1e-5, kE, kNu), std::invalid_argument);
}

TEST_CASE("the tractions' radial moments are the closed-form averages of |ξ|^2m over the disc",
          "[physics][interaction]") {
  // Uniform: ∫ r^2m 2r dr / a² = a^2m/(m+1). Rigid punch: ∫ r^2m r dr / (a sqrt(a² − r²)) = a^2m
  // 2^m m!/(2m+1)!!, here by Gauss–Legendre in r = a sin θ (smooth in θ).
  using G = boost::math::quadrature::gauss<double, 40>;
  for (int m = 0; m <= 8; ++m) {
    CHECK_THAT(traction_radial_moment(m, TractionWeighting::uniform), WithinRel(1.0 / (m + 1), 1e-15));
    const double rigid = G::integrate([m](double th) { return std::pow(std::sin(th), 2 * m + 1); }, 0.0, M_PI / 2);
    CHECK_THAT(traction_radial_moment(m, TractionWeighting::rigid), WithinRel(rigid, 1e-13));
  }
}

TEST_CASE("rigid weighting: the punch's traction displaces its own disc uniformly by Mindlin's compliance",
          "[physics][interaction]") {
  // Johnson §7.2: q = T/(2πa sqrt(a² − r²)) gives u_x = (2 − ν)/(8Ga) T all over the disc, so a
  // junction weighted by its own traction keeps Mindlin's self-compliance on the diagonal. The
  // ray integral is exact; the angular trapezoid converges spectrally (measured: ≤ 2e-15 with 256
  // nodes at |P| ≤ 0.9a).
  const double a = 1e-5, G = kE / (2 * (1 + kNu));
  const double mindlin = (2 - kNu) / (8 * G * a);
  for (const double nu : {0.0, 0.3, kNu}) {
    const double Gn = kE / (2 * (1 + nu));
    for (const auto& [x, y] :
         std::vector<std::pair<double, double>>{{0, 0}, {0.5e-5, 0}, {0, 0.7e-5}, {0.6e-5, -0.6e-5}}) {
      INFO("nu " << nu << " at (" << x << ", " << y << ")");
      CHECK_THAT(rigid_punch_displacement(x, y, a, kE, nu), WithinRel((2 - nu) / (8 * Gn * a), 1e-13));
    }
  }
  CHECK_THAT(rigid_punch_displacement(0, 0, a, kE, kNu), WithinRel(mindlin, 1e-14));
  CHECK_THROWS_AS(rigid_punch_displacement(1e-5, 0, a, kE, kNu), std::invalid_argument);
}

TEST_CASE("rigid weighting: the series equals a direct integration over two punch tractions",
          "[physics][interaction]") {
  struct Case {
    double dx, dy, a, b, tol;
    int n_theta;
  };
  // Gaps ≥ 0.2 radii (1e-8 asked by issue 22). Measured: ≤ 2.7e-13 at a gap of one radius or
  // more (64 angles), ≤ 1.0e-12 at 0.2 radii (128 angles): the quadrature's limit.
  const Case cases[] = {
      {3e-5, 0, 1e-5, 1e-5, 1e-12, 64},    {0, 3e-5, 1e-5, 1e-5, 1e-12, 64},
      {2e-5, 2e-5, 1e-5, 5e-6, 1e-12, 64}, {2.2e-5, 0, 1e-5, 1e-5, 4e-12, 128},
      {0, 2.2e-5, 1e-5, 1e-5, 4e-12, 128}, {1.8e-5, 0.6e-5, 1e-5, 0.4e-5, 4e-12, 128},
  };
  for (const Case& k : cases) {
    const double direct = direct_rigid_average(k.dx, k.dy, k.a, k.b, k.n_theta);
    const double series = disc_compliance(k.dx, k.dy, k.a, k.b, kE, kNu, TractionWeighting::rigid);
    INFO("dx " << k.dx << " dy " << k.dy << " a " << k.a << " b " << k.b << ": relative difference "
               << std::abs(series / direct - 1));
    CHECK_THAT(series, WithinRel(direct, k.tol));
  }
  // Symmetric (Betti), the point kernel for point discs, and stronger than uniform weighting for
  // near neighbours (the edge, nearest the neighbour, carries more of the traction).
  CHECK_THAT(disc_compliance(3e-5, 1e-5, 1e-5, 4e-6, kE, kNu, TractionWeighting::rigid),
             WithinRel(disc_compliance(-3e-5, -1e-5, 4e-6, 1e-5, kE, kNu, TractionWeighting::rigid), 1e-15));
  CHECK_THAT(disc_compliance(3e-5, 1e-5, 0, 0, kE, kNu, TractionWeighting::rigid),
             WithinRel(cerruti_compliance(3e-5, 1e-5, kE, kNu), 1e-15));
  for (const auto& [dx, dy] : std::vector<std::pair<double, double>>{{2.2e-5, 0}, {0, 2.2e-5}})
    CHECK(disc_compliance(dx, dy, 1e-5, 1e-5, kE, kNu, TractionWeighting::rigid) >
          disc_compliance(dx, dy, 1e-5, 1e-5, kE, kNu));
}
