#include "solve/interacting/anderson.hpp"

#include <cmath>

namespace asperity {

void Anderson::clear() {
  has_prev_ = false;
  dR_.clear();
  dG_.clear();
}

bool Anderson::step(const std::vector<double>& z, std::vector<double>& g) {
  std::vector<double> r(n_);
  for (std::size_t k = 0; k < n_; ++k) r[k] = g[k] - z[k];
  if (has_prev_) {
    std::vector<double> dr(n_), dg(n_);
    for (std::size_t k = 0; k < n_; ++k) dr[k] = r[k] - r_prev_[k], dg[k] = g[k] - g_prev_[k];
    dR_.push_back(std::move(dr));
    dG_.push_back(std::move(dg));
    if (dR_.size() > depth_) dR_.pop_front(), dG_.pop_front();
  }
  r_prev_ = r;
  g_prev_ = g;
  has_prev_ = true;
  const std::size_t m = dR_.size();
  if (m == 0) return false;
  // Normal equations (m ≤ depth, tiny), regularised relative to their scale: the differences
  // become nearly parallel as the iteration converges.
  double A[8][8] = {}, b[8] = {};
  if (m > 8) return false;
  double trace = 0;
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      double s = 0;
      for (std::size_t k = 0; k < n_; ++k) s += dR_[i][k] * dR_[j][k];
      A[i][j] = A[j][i] = s;
    }
    double s = 0;
    for (std::size_t k = 0; k < n_; ++k) s += dR_[i][k] * r[k];
    b[i] = s;
    trace += A[i][i];
  }
  if (!(trace > 0) || !std::isfinite(trace)) {
    clear();
    return false;
  }
  for (std::size_t i = 0; i < m; ++i) A[i][i] += 1e-12 * trace;
  // Cholesky in place, then the two triangular solves.
  for (std::size_t j = 0; j < m; ++j) {
    double d = A[j][j];
    for (std::size_t k = 0; k < j; ++k) d -= A[j][k] * A[j][k];
    if (!(d > 0)) {
      clear();
      return false;
    }
    A[j][j] = std::sqrt(d);
    for (std::size_t i = j + 1; i < m; ++i) {
      double s = A[i][j];
      for (std::size_t k = 0; k < j; ++k) s -= A[i][k] * A[j][k];
      A[i][j] = s / A[j][j];
    }
  }
  double gamma[8];
  for (std::size_t i = 0; i < m; ++i) {
    double s = b[i];
    for (std::size_t k = 0; k < i; ++k) s -= A[i][k] * gamma[k];
    gamma[i] = s / A[i][i];
  }
  for (std::size_t i = m; i-- > 0;) {
    double s = gamma[i];
    for (std::size_t k = i + 1; k < m; ++k) s -= A[k][i] * gamma[k];
    gamma[i] = s / A[i][i];
  }
  for (std::size_t i = 0; i < m; ++i)
    if (!std::isfinite(gamma[i]) || std::abs(gamma[i]) > 1e6) {
      clear();
      return false;
    }
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < n_; ++k) g[k] -= gamma[i] * dG_[i][k];
  return true;
}

}  // namespace asperity
