#pragma once
// The objectives of a fit (fit_spec.hpp): each experiment's share, from one run of its scene.
#include <span>
#include <vector>

#include "fit/fit_spec.hpp"
#include "observe/area_at.hpp"  // model_area_at: the area_and_force objective's A(Q)
#include "observe/observables.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

// Model force at the times t (s): the run's series (samples at k·every) linearly interpolated,
// the first or last sample outside it. NaN everywhere without a series.
std::vector<double> model_force_at(const std::vector<Sample>& series, std::span<const double> t);

// The area_and_force term of one experiment, by part. Each residual is divided by its noise
// level (FitNoise), so each part is a chi-square of its samples:
//   area   = Σ_j ((A_model(Q_j) − A_j) / (noise.area · Σ A0))²    measured A(Q) (model_area_at)
//   force  = Σ_k ((Q_model(t_k) − Q_k) / (noise.force · max_k Q_k))²   measured Q(t), by score:
//            pointwise: every sample k;
//            loading_and_cycles: the samples to the measured first peak (its sample included),
//            with the model's Q held at its own first peak after it (both peaks read at the
//            measured instants by sampled_cycles, below): a model whose peak comes early or late
//            is scored by a curve that moves continuously with it;
//   cycles = loading_and_cycles: both curves read at the measured instants by sampled_cycles
//            (observe/sampled_cycles.hpp; the scene's output.peak_min_drop, a floor of 5 σ_Q, peaks
//            from half the measured max_k Q_k: start-up ringing and precursors are no peaks):
//            ((drop − drop_m)/σ_drop)² when the measured curve shows n_d ≥ 1 drops with their
//            troughs, plus ((period − period_m)/σ_period)² when it shows n_p ≥ 1 complete cycles;
//            means over the first n_d (n_p) ≤ 5 of each curve. The deviations are the
//            estimator's, from the data: with σ_Q = noise.force · max_k Q_k, sampling interval dt
//            and r the rate at which Q rises into a peak (drop_m/period_m, else the first peak's
//            Q/t), a sampled maximum misses the true one by up to r·dt (uniform), so
//            σ_drop² = (2 σ_Q² + (r dt)²/6)/n_d; each drop is timed within its interval on both
//            curves, so σ_period = dt/(√3 n_p) (the mean period telescopes to (t_n − t_0)/n).
//            The model's drops are taken at its first n_d peaks, each to its lowest Q so far (a
//            measured trough seen only by grace of the noise at the window's end must not
//            cost the model its drop); a model without peaks (periods) counts as drop (period) = 0.
//            loading_and_peaks: the measured curve's first six peaks (five cycles) each paired by
//            time with the model's peaks (observe/peak_pairing.hpp), two residuals per measured
//            peak: a pair costs its t_cross difference over σ_t = dt/√6 (each timed within its
//            interval) plus its drop difference over one peak's σ_drop (n_d = 1 above); a peak
//            left unpaired costs its drop's excess over its threshold in σ_drop, faded over half
//            a measured period before the compared span ends (midway to the seventh measured
//            peak, else the window's end). A precursor near the threshold that noise finds in
//            one curve and not the other then costs about nothing, where pairing by order
//            compares every later peak with the wrong one.
//            Both: a measured curve without a peak is all loading branch, and gives no cycle term
//            (the model's late peaks are then scored pointwise by the held-peak branch).
//            auto: loading_and_cycles where the measured Q(t) shows two complete cycles or more
//            (n_p ≥ 2), else pointwise: through the first cycle the phase has had no time to
//            drift, the samples after the peak still inform, and pointwise recovers the truth
//            (tests/unit/studies/test_model_recovery.cpp); over several cycles its minimum is a
//            needle (docs/calibration.md, "The objective's landscape").
//   stick_slip = ((drop/drop_t − 1)² + (period/period_t − 1)²) / noise.stick_slip²  (a target
//                given; no stick-slip counts as drop = period = 0), else 0.
// Why two scores: pointwise, the stick-slip after the peak makes the objective jump as a cycle
// moves past a sample (docs/calibration.md, "The objective's landscape").
// n_*: the number of residuals of each part (for the reduced chi-square).
struct JointTerms {
  ForceScore score = ForceScore::pointwise;  // as applied (auto resolved)
  double area = 0, force = 0, cycles = 0, stick_slip = 0;
  int n_area = 0, n_force = 0, n_cycles = 0, n_stick_slip = 0;
  double total() const { return area + force + cycles + stick_slip; }
  int count() const { return n_area + n_force + n_cycles + n_stick_slip; }
};
JointTerms area_and_force_terms(const Scene& scene, const Observables& obs, const std::vector<Sample>& loading,
                                const std::vector<Sample>& series, const FitExperiment& experiment,
                                const FitNoise& noise, ForceScore score);

// The number of residuals behind one experiment's term of an area_and_force objective.
int area_and_force_count(const Scene& scene, const FitExperiment& experiment, const FitNoise& noise, ForceScore score);

// One experiment's term of the objective. NaN when the run gives no value to compare (e.g. no
// loading branch); a run without stick-slip counts as drop = period = 0 for stick_slip.
double experiment_residual(FitObjective objective, const Scene& scene, const Observables& obs,
                           const std::vector<Sample>& loading, const StickSlipTarget& target);

}  // namespace asperity
