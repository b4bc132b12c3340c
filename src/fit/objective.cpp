#include "fit/objective.hpp"

#include <algorithm>
#include <cmath>

namespace asperity {

std::vector<double> model_force_at(const std::vector<Sample>& series, std::span<const double> t) {
  std::vector<double> out(t.size(), Observables::nan);
  if (series.empty()) return out;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double x = t[k];
    if (x <= series.front().t) {
      out[k] = series.front().Q;
    } else if (x >= series.back().t) {
      out[k] = series.back().Q;
    } else {
      const auto it = std::upper_bound(series.begin(), series.end(), x, [](double v, const Sample& s) { return v < s.t; });
      const Sample& b = *it;
      const Sample& a = *(it - 1);  // a.t <= x < b.t
      out[k] = b.t > a.t ? a.Q + (x - a.t) / (b.t - a.t) * (b.Q - a.Q) : a.Q;
    }
  }
  return out;
}

int area_and_force_count(const Scene& scene, const FitExperiment& fe) {
  int n = 0;
  if (scene.experiment.measured) n += static_cast<int>(scene.experiment.measured->Q_N.size());
  if (fe.force) n += static_cast<int>(fe.force->t_s.size());
  if (fe.has_target()) n += 2;
  return n;
}

JointTerms area_and_force_terms(const Scene& scene, const Observables& obs, const std::vector<Sample>& loading,
                                const std::vector<Sample>& series, const FitExperiment& fe, const FitNoise& noise) {
  JointTerms t;
  if (scene.experiment.measured && !scene.experiment.measured->Q_N.empty()) {
    const MeasuredCurve& m = *scene.experiment.measured;
    const std::vector<double> A = model_area_at(loading, obs.Q_s, obs.A_s, m.Q_N);
    const double scale = noise.area * obs.A0;
    for (std::size_t j = 0; j < A.size(); ++j) {
      const double r = (A[j] - m.A_m2[j]) / scale;
      t.area += r * r;
    }
    t.n_area = static_cast<int>(A.size());
  }
  if (fe.force && !fe.force->t_s.empty()) {
    const MeasuredForce& f = *fe.force;
    const double Q_max = *std::max_element(f.Q_N.begin(), f.Q_N.end());
    const double scale = noise.force * Q_max;
    const std::vector<double> Q = model_force_at(series, f.t_s);
    for (std::size_t k = 0; k < Q.size(); ++k) {
      const double r = (Q[k] - f.Q_N[k]) / scale;
      t.force += r * r;
    }
    t.n_force = static_cast<int>(Q.size());
  }
  if (fe.has_target()) {
    const bool has = obs.ss_cycles > 0;
    const double rd = ((has ? obs.ss_drop : 0.0) / fe.target.drop_N - 1.0) / noise.stick_slip;
    const double rp = ((has ? obs.ss_period : 0.0) / fe.target.period_s - 1.0) / noise.stick_slip;
    t.stick_slip = rd * rd + rp * rp;
    t.n_stick_slip = 2;
  }
  return t;
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
    case FitObjective::area_and_force:  // needs the series and the force curve: area_and_force_terms
    case FitObjective::user: break;     // the caller's term (fit.cpp)
  }
  return Observables::nan;
}

}  // namespace asperity
