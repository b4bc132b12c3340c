#include "observe/sampled_cycles.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace asperity {

SampledCycles sampled_cycles(std::span<const double> t, std::span<const double> Q, double min_drop, double floor_N,
                             int n, double min_peak_N) {
  if (t.size() != Q.size()) throw std::invalid_argument("sampled_cycles: t and Q differ in length");
  if (n < 1) throw std::invalid_argument("sampled_cycles: n must be ≥ 1");
  SampledCycles out;
  if (t.empty() || !std::all_of(Q.begin(), Q.end(), [](double q) { return std::isfinite(q); })) return out;
  const auto fall_of = [&](double q_max) { return std::max(min_drop * q_max, floor_N); };
  bool seeking_max = true;
  std::size_t top = 0, trough = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (seeking_max) {
      if (Q[k] > Q[top]) {
        top = k;
      } else if (const double level = Q[top] - fall_of(Q[top]); Q[k] < level && Q[top] >= min_peak_N) {
        // Q[k - 1] ≥ level > Q[k]: the crossing lies in this interval.
        const double w = (Q[k - 1] - level) / (Q[k - 1] - Q[k]);
        out.peaks.push_back({t[top], Q[top], t[k - 1] + w * (t[k] - t[k - 1]), Q[k], false, fall_of(Q[top])});
        seeking_max = false;
        trough = k;
      }
    } else if (Q[k] < Q[trough]) {
      trough = k;
      out.peaks.back().Q_min = Q[k];
    } else if (Q[k] > Q[trough] + fall_of(out.peaks.back().Q_max)) {
      out.peaks.back().trough_seen = true;
      seeking_max = true;
      top = k;
    }
  }
  const std::size_t cap = static_cast<std::size_t>(n);
  double drop = 0, period = 0;
  for (std::size_t j = 0; j < out.peaks.size() && static_cast<std::size_t>(out.n_drops) < cap; ++j)
    if (out.peaks[j].trough_seen) {
      drop += out.peaks[j].Q_max - out.peaks[j].Q_min;
      ++out.n_drops;
    }
  for (std::size_t j = 0; j + 1 < out.peaks.size() && static_cast<std::size_t>(out.n_periods) < cap; ++j) {
    period += out.peaks[j + 1].t_cross - out.peaks[j].t_cross;
    ++out.n_periods;
  }
  if (out.n_drops > 0) out.mean_drop = drop / out.n_drops;
  if (out.n_periods > 0) out.mean_period = period / out.n_periods;
  return out;
}

}  // namespace asperity
