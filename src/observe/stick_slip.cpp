#include "observe/stick_slip.hpp"

#include <algorithm>
#include <stdexcept>

namespace asperity {

StickSlipStats stick_slip_stats(const std::vector<Peak>& peaks, int n) {
  if (n < 1) throw std::invalid_argument("stick_slip_stats: n must be ≥ 1");
  StickSlipStats s;
  const int complete = peaks.size() < 2 ? 0 : static_cast<int>(peaks.size()) - 1;
  s.n_cycles = std::min(n, complete);
  if (s.n_cycles == 0) return s;
  double drop = 0, period = 0;
  for (int j = 0; j < s.n_cycles; ++j) {
    const auto& p = peaks[static_cast<std::size_t>(j)];
    drop += p.max.Q - p.min.Q;
    period += peaks[static_cast<std::size_t>(j) + 1].max.t - p.max.t;
  }
  s.mean_drop = drop / s.n_cycles;
  s.mean_period = period / s.n_cycles;
  return s;
}

}  // namespace asperity
