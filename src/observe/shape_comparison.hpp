#pragma once
// A model's A(Q) against a measured one at the measurement's own noise.
// The shape exponent n of a log-log fit is dominated by the noise at small Q (exact parabolas
// with 0.2 % noise give n from 1.7 to 2.1), so a verdict on shape needs measures whose spread
// over that noise is known:
//  - the quadratic coefficient α of A = A0 − α Q² (A0 fixed), model and measured, with the
//    measured one's standard deviation;
//  - the rms residual of the model's A(Q) at the measured Q, in linear space, against the rms a
//    model that were exactly the measured curve's best parabola would leave (noise alone);
// both spreads by a residual bootstrap of the measured curve (its residuals about its own
// quadratic fit, resampled with replacement onto that fit: B seeded resamples), as is n's.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "solve/core/observer.hpp"

namespace asperity {

struct MeasuredCurve;  // scene/scene.hpp

struct ShapeComparison {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double alpha_model = nan;        // m²/N², fit of the model's loading branch
  double alpha_measured = nan;     // m²/N², fit of the measured points
  double alpha_measured_sd = nan;  // m²/N², its bootstrap standard deviation
  double n_model = nan;            // shape exponent of A0 − A ∝ Qⁿ, model
  double n_measured = nan;         // the same of the measured points
  double n_measured_sd = nan;      // its bootstrap standard deviation
  double residual_rms = nan;       // m², rms of A_model(Q_i) − A_i over the measured points used
  double residual_rms_sd = nan;    // m², its bootstrap standard deviation (the measured points resampled)
  double noise_rms = nan;          // m², rms of the measured points about their own parabola
  double noise_rms_p95 = nan;      // m², 95th percentile of that rms over the bootstrap
  std::size_t points_used = 0;     // measured points within the model's loading branch
  std::size_t resamples = 0;
  // |α_model − α_measured| > 2 sd: the model's curvature differs from the measured one beyond
  // the noise; false means no evidence of a difference (not proof of agreement).
  bool alpha_differs() const { return std::abs(alpha_model - alpha_measured) > 2 * alpha_measured_sd; }
  // The model's residual exceeds what noise alone leaves in 95 % of the resamples.
  bool residual_exceeds_noise() const { return residual_rms > noise_rms_p95; }
};

// `loading`: the model's loading branch (samples up to the first peak, Recorder::loading_branch);
// A0 [m²]: the initial area both fits use. Deterministic for a given seed.
ShapeComparison compare_shapes(const std::vector<Sample>& loading, const MeasuredCurve& measured, double A0,
                               std::uint64_t seed = 20201203, std::size_t resamples = 1000);

// The bootstrap part alone, on a measured curve (Q, A) with A0 fixed: fills alpha_measured,
// alpha_measured_sd, n_measured, n_measured_sd, noise_rms and noise_rms_p95.
ShapeComparison bootstrap_measured(const std::vector<double>& Q, const std::vector<double>& A, double A0,
                                   std::uint64_t seed, std::size_t resamples);

}  // namespace asperity
