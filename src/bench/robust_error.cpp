#include "bench/robust_error.hpp"

#include <cmath>

namespace asperity {

const std::array<std::string, n_robust>& robust_names() {
  static const std::array<std::string, n_robust> names{"Q_s", "A_s", "t_peak", "alpha", "ss_drop", "ss_period"};
  return names;
}

const std::array<double, n_robust>& robust_targets() {
  static const std::array<double, n_robust> targets{1e-4, 1e-4, 1e-4, 1e-4, 1e-2, 1e-2};
  return targets;
}

std::array<double, n_robust> robust_values(const Observables& o) {
  std::array<double, n_robust> v{};
  for (std::size_t i = 0; i < n_robust; ++i) v[i] = observable_field(robust_names()[i]).value(o);
  return v;
}

std::array<double, n_robust> relative_errors(const Observables& run, const Observables& converged) {
  const auto a = robust_values(run), b = robust_values(converged);
  std::array<double, n_robust> e{};
  for (std::size_t i = 0; i < n_robust; ++i) e[i] = std::abs(a[i] - b[i]) / std::abs(b[i]);
  return e;
}

}  // namespace asperity
