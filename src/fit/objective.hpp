#pragma once
// The objectives of a fit (fit_spec.hpp): each experiment's share, from one run of its scene.
#include <span>
#include <vector>

#include "fit/fit_spec.hpp"
#include "observe/observables.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

// Model area at the forces Q (N) from the loading branch: A(Q) along the samples whose Q
// exceeds every earlier Q (the branch made monotone: ringing after single slips would make
// A(Q) multivalued), linearly interpolated, the peak (Q_s, A_s) appended when beyond the last
// sample. For Q above the peak force the model has slid: its area stays A_s there.
std::vector<double> model_area_at(const std::vector<Sample>& loading, double Q_s, double A_s,
                                  std::span<const double> Q);

// One experiment's term of the objective. NaN when the run gives no value to compare (e.g. no
// loading branch); a run without stick-slip counts as drop = period = 0 for stick_slip.
double experiment_residual(FitObjective objective, const Scene& scene, const Observables& obs,
                           const std::vector<Sample>& loading, const StickSlipTarget& target);

}  // namespace asperity
