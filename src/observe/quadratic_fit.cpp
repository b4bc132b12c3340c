#include "observe/quadratic_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/scene.hpp"

namespace asperity {
namespace {

void check_sizes(std::span<const double> Q, std::span<const double> A) {
  if (Q.size() != A.size())
    throw std::invalid_argument("A(Q) fit: Q and A have different lengths (" + std::to_string(Q.size()) + " vs " +
                                std::to_string(A.size()) + ")");
}

// Column of Q and A out of samples, so that both kinds of input share one implementation.
struct Columns {
  std::vector<double> Q, A;
  explicit Columns(const std::vector<Sample>& s) {
    Q.reserve(s.size());
    A.reserve(s.size());
    for (const auto& x : s) {
      Q.push_back(x.Q);
      A.push_back(x.A);
    }
  }
};

}  // namespace

QuadraticFit fit_quadratic_area(std::span<const double> Q, std::span<const double> A, double A0) {
  check_sizes(Q, A);
  QuadraticFit fit;
  std::vector<std::size_t> use;
  use.reserve(Q.size());
  for (std::size_t i = 0; i < Q.size(); ++i)
    if (std::isfinite(Q[i]) && std::isfinite(A[i])) use.push_back(i);
  fit.n_points = use.size();
  const auto n = static_cast<Eigen::Index>(use.size());
  if (n == 0 || !std::isfinite(A0)) return fit;

  // One unknown: (A0 − A) = α Q². Solved by QR on the column Q² (well conditioned whatever the
  // units: the column is scaled by its own norm inside the Householder step).
  Eigen::MatrixXd D(n, 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t i = use[static_cast<std::size_t>(r)];
    D(r, 0) = Q[i] * Q[i];
    y(r) = A0 - A[i];
  }
  if (D.col(0).cwiseAbs().maxCoeff() == 0.0) return fit;
  fit.alpha = D.colPivHouseholderQr().solve(y)(0);

  double mean = 0;
  for (std::size_t i : use) mean += A[i];
  mean /= static_cast<double>(n);
  double ss_res = 0, ss_tot = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t i = use[static_cast<std::size_t>(r)];
    const double res = y(r) - fit.alpha * D(r, 0);
    ss_res += res * res;
    ss_tot += (A[i] - mean) * (A[i] - mean);
  }
  if (ss_tot > 0) fit.R2 = 1.0 - ss_res / ss_tot;
  return fit;
}

QuadraticFit fit_quadratic_area(const std::vector<Sample>& loading, double A0) {
  const Columns c(loading);
  return fit_quadratic_area(c.Q, c.A, A0);
}

QuadraticFit fit_quadratic_area(const MeasuredCurve& curve, double A0) {
  return fit_quadratic_area(curve.Q_N, curve.A_m2, A0);
}

ShapeIndex fit_power_law(std::span<const double> Q, std::span<const double> A, double A0, double q_min_fraction) {
  check_sizes(Q, A);
  ShapeIndex s;
  double q_max = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < Q.size(); ++i)
    if (std::isfinite(Q[i]) && std::isfinite(A[i])) q_max = std::max(q_max, Q[i]);
  if (!(q_max > 0) || !std::isfinite(A0)) return s;
  const double q_lo = q_min_fraction * q_max;

  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < Q.size(); ++i) {
    if (!std::isfinite(Q[i]) || !std::isfinite(A[i])) continue;
    const double dA = A0 - A[i];
    if (Q[i] > q_lo && Q[i] > 0 && dA > 0) {
      lx.push_back(std::log(Q[i]));
      ly.push_back(std::log(dA));
    }
  }
  s.n_points = lx.size();
  if (lx.size() < 2 || *std::max_element(lx.begin(), lx.end()) == *std::min_element(lx.begin(), lx.end())) return s;

  const auto n = static_cast<Eigen::Index>(lx.size());
  Eigen::MatrixXd D(n, 2);
  Eigen::VectorXd y(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    D(r, 0) = 1.0;
    D(r, 1) = lx[static_cast<std::size_t>(r)];
    y(r) = ly[static_cast<std::size_t>(r)];
  }
  const Eigen::Vector2d b = D.colPivHouseholderQr().solve(y);
  s.c = std::exp(b(0));
  s.n = b(1);
  const double mean = y.mean();
  const double ss_res = (y - D * b).squaredNorm();
  const double ss_tot = (y.array() - mean).square().sum();
  if (ss_tot > 0) s.R2_log = 1.0 - ss_res / ss_tot;
  return s;
}

ShapeIndex fit_power_law(const std::vector<Sample>& loading, double A0, double q_min_fraction) {
  const Columns c(loading);
  return fit_power_law(c.Q, c.A, A0, q_min_fraction);
}

ShapeIndex fit_power_law(const MeasuredCurve& curve, double A0, double q_min_fraction) {
  return fit_power_law(curve.Q_N, curve.A_m2, A0, q_min_fraction);
}

}  // namespace asperity
