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
//   force  = Σ_k ((Q_model(t_k) − Q_k) / (noise.force · max_k Q_k))²   measured Q(t)
//   stick_slip = ((drop/drop_t − 1)² + (period/period_t − 1)²) / noise.stick_slip²  (a target
//                given; no stick-slip counts as drop = period = 0), else 0.
// n_*: the number of residuals of each part (for the reduced chi-square).
struct JointTerms {
  double area = 0, force = 0, stick_slip = 0;
  int n_area = 0, n_force = 0, n_stick_slip = 0;
  double total() const { return area + force + stick_slip; }
  int count() const { return n_area + n_force + n_stick_slip; }
};
JointTerms area_and_force_terms(const Scene& scene, const Observables& obs, const std::vector<Sample>& loading,
                                const std::vector<Sample>& series, const FitExperiment& experiment,
                                const FitNoise& noise);

// The number of residuals behind one experiment's term of an area_and_force objective.
int area_and_force_count(const Scene& scene, const FitExperiment& experiment);

// One experiment's term of the objective. NaN when the run gives no value to compare (e.g. no
// loading branch); a run without stick-slip counts as drop = period = 0 for stick_slip.
double experiment_residual(FitObjective objective, const Scene& scene, const Observables& obs,
                           const std::vector<Sample>& loading, const StickSlipTarget& target);

}  // namespace asperity
