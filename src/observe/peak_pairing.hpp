#pragma once
// The peaks of a measured and a model Q(t), both read by sampled_cycles, paired by time.
//
// Pairing by order fails where a curve holds a fall near the estimator's threshold: noise then
// finds it in one realization and not in the next, and the i-th peaks of the two curves become
// different events (docs/calibration.md, "The Q(t) score"). Here the pairing is the monotone
// alignment of least cost:
//   a pair (measured i, model j):  ((t_j − t_i)/σ_t)² + ((drop_j − drop_i)/σ_drop)²,
//   a peak left unpaired:          w(t) ((drop − fall)/σ_drop)²,
// with t a peak's t_cross, drop = Q_max − Q_min and fall the threshold that made it a peak. An
// unpaired peak costs how far its drop stands above the threshold in noise units: a marginal
// precursor costs almost nothing, a main slip much. The cost is a minimum over alignments of
// terms that each move continuously with the curves (a peak appears with zero excess), so it has
// no jumps where a peak appears or a pairing changes. w(t) = clamp((t_window − t)/taper, 0, 1)
// fades a peak whose partner may lie past the end of what is compared.
#include <span>

#include "observe/sampled_cycles.hpp"

namespace asperity {

struct PeakPairingScale {
  double sigma_t_s = 0;     // deviation of the difference of two paired peaks' t_cross
  double sigma_drop_N = 0;  // deviation of one peak's drop (and of a drop's excess over its fall)
  double t_window_s = 0;    // peaks are compared up to here: an unpaired one costs nothing after it
  double taper_s = 0;       // the fade before t_window_s (> 0)
};

struct PeakPairing {
  double chi2 = 0;  // the least cost
  int pairs = 0, unpaired_measured = 0, unpaired_model = 0;
};

// measured: the peaks compared (the caller picks which); model: every peak of the model's curve.
PeakPairing pair_peaks(std::span<const SampledPeak> measured, std::span<const SampledPeak> model,
                       const PeakPairingScale& scale);

}  // namespace asperity
