#include "observe/peak_pairing.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

namespace asperity {

namespace {

double square(double x) { return x * x; }

double drop_of(const SampledPeak& p) { return p.Q_max - p.Q_min; }

}  // namespace

PeakPairing pair_peaks(std::span<const SampledPeak> measured, std::span<const SampledPeak> model,
                       const PeakPairingScale& s) {
  if (!(s.sigma_t_s > 0) || !(s.sigma_drop_N > 0) || !(s.taper_s > 0))
    throw std::invalid_argument("pair_peaks: the deviations and the taper must be positive");
  const auto unpaired = [&](const SampledPeak& p) {
    const double w = std::clamp((s.t_window_s - p.t_cross) / s.taper_s, 0.0, 1.0);
    return w * square((drop_of(p) - p.fall_N) / s.sigma_drop_N);
  };
  const auto paired = [&](const SampledPeak& a, const SampledPeak& b) {
    return square((b.t_cross - a.t_cross) / s.sigma_t_s) + square((drop_of(b) - drop_of(a)) / s.sigma_drop_N);
  };
  // cost[i][j]: the least cost of the first i measured and the first j model peaks; step records
  // the last move (0 measured unpaired, 1 model unpaired, 2 a pair) for the counts.
  const std::size_t m = measured.size(), n = model.size();
  std::vector<double> cost((m + 1) * (n + 1), 0.0);
  std::vector<unsigned char> step((m + 1) * (n + 1), 0);
  const auto at = [n](std::size_t i, std::size_t j) { return i * (n + 1) + j; };
  for (std::size_t i = 0; i <= m; ++i)
    for (std::size_t j = 0; j <= n; ++j) {
      if (i == 0 && j == 0) continue;
      double best = std::numeric_limits<double>::infinity();
      unsigned char move = 0;
      const auto consider = [&](double c, unsigned char mv) {
        if (c < best) best = c, move = mv;
      };
      if (i > 0) consider(cost[at(i - 1, j)] + unpaired(measured[i - 1]), 0);
      if (j > 0) consider(cost[at(i, j - 1)] + unpaired(model[j - 1]), 1);
      if (i > 0 && j > 0) consider(cost[at(i - 1, j - 1)] + paired(measured[i - 1], model[j - 1]), 2);
      cost[at(i, j)] = best;
      step[at(i, j)] = move;
    }
  PeakPairing out;
  out.chi2 = cost[at(m, n)];
  for (std::size_t i = m, j = n; i > 0 || j > 0;) {
    switch (step[at(i, j)]) {
      case 0:
        ++out.unpaired_measured, --i;
        break;
      case 1:
        ++out.unpaired_model, --j;
        break;
      default:
        ++out.pairs, --i, --j;
        break;
    }
  }
  return out;
}

}  // namespace asperity
