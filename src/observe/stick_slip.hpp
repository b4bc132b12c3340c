#pragma once
// Stick-slip statistics from the confirmed peaks of Q (docs/model.md §5: "amplitude and period of
// the drops"). Cycle j (j = 0 is the static peak Q_s) is complete once peak j + 1 is confirmed:
// its drop is Q_max,j − Q_min,j and its period t_max,j+1 − t_max,j. This is the same count the
// Recorder's stop.cycles uses (n cycles need n + 1 peaks).
#include <limits>
#include <vector>

#include "observe/recorder.hpp"

namespace asperity {

struct StickSlipStats {
  int n_cycles = 0;                                               // complete cycles averaged over (≤ the n asked for)
  double mean_drop = std::numeric_limits<double>::quiet_NaN();    // N, mean Q_max − Q_min
  double mean_period = std::numeric_limits<double>::quiet_NaN();  // s, mean time between peaks
};

// Over the first n complete cycles (n ≥ 1). NaN means when no cycle is complete (< 2 peaks).
StickSlipStats stick_slip_stats(const std::vector<Peak>& peaks, int n = 5);

}  // namespace asperity
