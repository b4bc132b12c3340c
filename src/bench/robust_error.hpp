#pragma once
// The robust observables a solver is judged on (docs/model.md §4: not late-time pointwise
// trajectories) and their relative errors against a converged run.
#include <array>
#include <string>

#include "observe/observables.hpp"

namespace asperity {

inline constexpr std::size_t n_robust = 6;
// Column names, in the order of robust_values(): Q_s, A_s, t_peak, alpha, ss_drop, ss_period.
const std::array<std::string, n_robust>& robust_names();

// Issue 3 targets at the default tolerance: 1e-4 relative for the loading branch
// (Q_s, A_s, t_peak, alpha), 1e-2 for the stick-slip means (ss_drop, ss_period).
const std::array<double, n_robust>& robust_targets();

std::array<double, n_robust> robust_values(const Observables& o);

// |x − x_conv| / |x_conv| per observable; NaN when either is NaN (e.g. no stick-slip cycle).
std::array<double, n_robust> relative_errors(const Observables& run, const Observables& converged);

}  // namespace asperity
