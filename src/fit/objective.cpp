#include "fit/objective.hpp"

#include <algorithm>
#include <cmath>

namespace asperity {

std::vector<double> model_area_at(const std::vector<Sample>& loading, double Q_s, double A_s,
                                  std::span<const double> Q) {
  std::vector<double> q, a;
  for (const auto& s : loading)
    if (std::isfinite(s.Q) && std::isfinite(s.A) && (q.empty() || s.Q > q.back())) {
      q.push_back(s.Q);
      a.push_back(s.A);
    }
  if (std::isfinite(Q_s) && std::isfinite(A_s) && (q.empty() || Q_s > q.back())) {
    q.push_back(Q_s);
    a.push_back(A_s);
  }
  std::vector<double> out(Q.size(), Observables::nan);
  if (q.empty()) return out;
  for (std::size_t j = 0; j < Q.size(); ++j) {
    const double x = Q[j];
    if (x <= q.front()) {
      out[j] = a.front();
    } else if (x >= q.back()) {
      out[j] = std::isfinite(A_s) ? A_s : a.back();
    } else {
      const auto it = std::upper_bound(q.begin(), q.end(), x);
      const std::size_t i = static_cast<std::size_t>(it - q.begin());  // q[i-1] <= x < q[i]
      const double w = (x - q[i - 1]) / (q[i] - q[i - 1]);
      out[j] = a[i - 1] + w * (a[i] - a[i - 1]);
    }
  }
  return out;
}

double experiment_residual(FitObjective objective, const Scene& scene, const Observables& obs,
                           const std::vector<Sample>& loading, const StickSlipTarget& target) {
  switch (objective) {
    case FitObjective::quadratic_alpha: {
      const double r = obs.alpha / obs.alpha_measured - 1.0;
      return r * r;
    }
    case FitObjective::area_curve: {
      if (!scene.experiment.measured || scene.experiment.measured->Q_N.empty()) return Observables::nan;
      const MeasuredCurve& m = *scene.experiment.measured;
      const std::vector<double> A = model_area_at(loading, obs.Q_s, obs.A_s, m.Q_N);
      double sum = 0;
      for (std::size_t j = 0; j < A.size(); ++j) {
        const double r = (A[j] - m.A_m2[j]) / obs.A0;
        sum += r * r;
      }
      return sum / static_cast<double>(A.size());
    }
    case FitObjective::stick_slip: {
      const bool has = obs.ss_cycles > 0;
      const double rd = (has ? obs.ss_drop : 0.0) / target.drop_N - 1.0;
      const double rp = (has ? obs.ss_period : 0.0) / target.period_s - 1.0;
      return rd * rd + rp * rp;
    }
    case FitObjective::user: break;  // the caller's term (fit.cpp)
  }
  return Observables::nan;
}

}  // namespace asperity
