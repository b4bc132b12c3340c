#pragma once
// Stick-slip cycles of a Q(t) known only at sample instants: a measured curve, or a run read at
// the measured instants. Reading both through this one estimator makes its sampling bias (a
// sampled maximum sits below the true one) the same on both sides of a comparison.
//
// A peak is a maximum of at least min_peak_N followed by a fall of at least
// max(min_drop · Q_max, floor_N) (floor_N: a few noise levels, so that noise never makes a peak;
// min_peak_N: a level below which a fall is start-up ringing or a precursor); its trough is the lowest Q before Q rises
// again by that much. A peak is timed by the instant Q first crosses Q_max − that fall,
// interpolated between samples: unlike the sample holding the maximum, it moves continuously
// with the curve, so a fitted period has no steps of one sampling interval.
#include <limits>
#include <span>
#include <vector>

namespace asperity {

struct SampledPeak {
  double t_max = 0, Q_max = 0;  // the sample holding the maximum (s, N)
  double t_cross = 0;           // s: when Q fell through Q_max − the fall
  double Q_min = 0;             // N: the trough so far
  bool trough_seen = false;     // Q rose again by the fall after it: Q_min is the trough
  double fall_N = 0;            // N: the fall that made it a peak (Q_max − Q_min ≥ fall_N)
};

struct SampledCycles {
  std::vector<SampledPeak> peaks;
  // Over the first n peaks whose trough was seen: the mean drop Q_max − Q_min (N); over the first
  // n complete cycles (peaks j and j + 1 found): the mean period t_cross,j+1 − t_cross,j (s).
  // NaN where the count is 0. A curve that ends in its first slip has neither; one that ends
  // after its first trough has a drop and no period.
  int n_drops = 0, n_periods = 0;
  double mean_drop = std::numeric_limits<double>::quiet_NaN();
  double mean_period = std::numeric_limits<double>::quiet_NaN();
};

// t_s increasing, Q_N the same length; no peak at all when a value is not finite.
SampledCycles sampled_cycles(std::span<const double> t_s, std::span<const double> Q_N, double min_drop, double floor_N,
                             int n = 5, double min_peak_N = 0);

}  // namespace asperity
