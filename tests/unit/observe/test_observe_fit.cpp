#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "observe/quadratic_fit.hpp"
#include "scene/scene.hpp"

using namespace asperity;

TEST_CASE("quadratic fit recovers alpha exactly on exact-quadratic data", "[observe]") {
  const double A0 = 12.7e-6, alpha = 3.1e-7;
  std::vector<Sample> s;
  for (int i = 0; i <= 200; ++i) {
    Sample x;
    x.t = 1e-3 * i;
    x.Q = 0.005 * i;  // up to 1 N
    x.A = A0 - alpha * x.Q * x.Q;
    s.push_back(x);
  }
  const QuadraticFit f = fit_quadratic_area(s, A0);
  CHECK(f.n_points == s.size());
  CHECK(f.alpha == Approx(alpha).epsilon(1e-14));
  CHECK(f.R2 == Approx(1.0).epsilon(1e-14));

  // The same through a measured curve (spans of Q and A).
  MeasuredCurve c;
  for (const auto& x : s) {
    c.Q_N.push_back(x.Q);
    c.A_m2.push_back(x.A);
  }
  const QuadraticFit g = fit_quadratic_area(c, A0);
  CHECK(g.alpha == Approx(alpha).epsilon(1e-14));
  CHECK(g.R2 == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("quadratic fit of linear data has R2 < 1 and the least-squares alpha", "[observe]") {
  // A0 − A = b Q on Q ∈ {1, 2}: α = Σ Q² b Q / Σ Q⁴ = b (1 + 8) / (1 + 16).
  const double A0 = 1.0, b = 0.1;
  const std::vector<double> Q{1.0, 2.0}, A{A0 - b * 1.0, A0 - b * 2.0};
  const QuadraticFit f = fit_quadratic_area(Q, A, A0);
  CHECK(f.alpha == Approx(b * 9.0 / 17.0).epsilon(1e-14));
  CHECK(f.R2 < 1.0);
}

TEST_CASE("quadratic fit degenerate inputs give NaN, not garbage", "[observe]") {
  const std::vector<double> none;
  CHECK(std::isnan(fit_quadratic_area(none, none, 1.0).alpha));
  const std::vector<double> Q0{0.0, 0.0}, A0v{1.0, 1.0};
  CHECK(std::isnan(fit_quadratic_area(Q0, A0v, 1.0).alpha));
  const std::vector<double> Q1{1.0};
  CHECK_THROWS(fit_quadratic_area(Q1, A0v, 1.0));
}

TEST_CASE("power-law exponent recovers n = 1 and n = 2", "[observe]") {
  const double A0 = 12.7e-6;
  for (double n : {1.0, 2.0, 1.37}) {
    const double c = 2.5e-6;
    std::vector<double> Q, A;
    for (int i = 0; i <= 300; ++i) {
      Q.push_back(1.2 * i / 300.0);
      A.push_back(A0 - c * std::pow(Q.back(), n));
    }
    const ShapeIndex s = fit_power_law(Q, A, A0);
    CHECK(s.n == Approx(n).epsilon(1e-14));
    CHECK(s.c == Approx(c).epsilon(2e-14));
    // Q > 0.05 Q_max: i > 15.
    CHECK(s.n_points == 300 - 15);
  }
}

TEST_CASE("power-law fit ignores points without area loss", "[observe]") {
  const double A0 = 1.0;
  const std::vector<double> Q{0.0, 0.5, 1.0, 2.0, 4.0}, A{1.0, 1.0, 1.0 - 0.01, 1.0 - 0.04, 1.0 - 0.16};
  const ShapeIndex s = fit_power_law(Q, A, A0);
  CHECK(s.n_points == 3);
  CHECK(s.n == Approx(2.0).epsilon(1e-14));
  const std::vector<double> Qd{1.0}, Ad{0.5};
  CHECK(std::isnan(fit_power_law(Qd, Ad, A0).n));
}
