#include "observe/area_at.hpp"

#include <algorithm>
#include <cmath>

namespace asperity {

std::vector<double> model_area_at(const std::vector<Sample>& loading, double Q_s, double A_s,
                                  std::span<const double> Q) {
  std::vector<double> q, a;
  for (const auto& s : loading)
    if (std::isfinite(s.Q) && std::isfinite(s.A) && (q.empty() || s.Q > q.back())) {
      q.push_back(s.Q);
      a.push_back(s.A);
    }
  if (std::isfinite(Q_s) && std::isfinite(A_s) && (q.empty() || Q_s > q.back())) {
    q.push_back(Q_s);
    a.push_back(A_s);
  }
  std::vector<double> out(Q.size(), Observables::nan);
  if (q.empty()) return out;
  for (std::size_t j = 0; j < Q.size(); ++j) {
    const double x = Q[j];
    if (x <= q.front()) {
      out[j] = a.front();
    } else if (x >= q.back()) {
      out[j] = std::isfinite(A_s) ? A_s : a.back();
    } else {
      const auto it = std::upper_bound(q.begin(), q.end(), x);
      const std::size_t i = static_cast<std::size_t>(it - q.begin());  // q[i-1] <= x < q[i]
      const double w = (x - q[i - 1]) / (q[i] - q[i - 1]);
      out[j] = a[i - 1] + w * (a[i] - a[i - 1]);
    }
  }
  return out;
}

}  // namespace asperity
