#pragma once
// The model's A(Q) at given forces, from a run's loading branch: what a fit compares with a
// measured A(Q) (fit/objective.hpp) and what a synthetic experiment writes as one
// (generate/synthetic.hpp), so both read the branch the same way.
#include <span>
#include <vector>

#include "observe/observables.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

// Model area at the forces Q (N) from the loading branch: A(Q) along the samples whose Q
// exceeds every earlier Q (the branch made monotone: ringing after single slips would make
// A(Q) multivalued), linearly interpolated, the peak (Q_s, A_s) appended when beyond the last
// sample. For Q above the peak force the model has slid: its area stays A_s there.
std::vector<double> model_area_at(const std::vector<Sample>& loading, double Q_s, double A_s,
                                  std::span<const double> Q);

}  // namespace asperity
