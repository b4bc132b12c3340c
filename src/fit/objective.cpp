#include "fit/objective.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "observe/peak_pairing.hpp"
#include "observe/sampled_cycles.hpp"

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
      const auto it =
          std::upper_bound(series.begin(), series.end(), x, [](double v, const Sample& s) { return v < s.t; });
      const Sample& b = *it;
      const Sample& a = *(it - 1);  // a.t <= x < b.t
      out[k] = b.t > a.t ? a.Q + (x - a.t) / (b.t - a.t) * (b.Q - a.Q) : a.Q;
    }
  }
  return out;
}

namespace {

// What loading_and_cycles reads from the measured Q(t): where its loading branch ends (the index
// one past the first peak's sample; every sample without a peak), its cycles, and the standard
// deviations of their mean drop and period (objective.hpp).
struct MeasuredShape {
  std::size_t loading_end = 0;
  SampledCycles cycles;
  double min_drop = 0, floor_N = 0, min_peak_N = 0;  // the estimator's settings, for the model's curve
  double sigma_drop_N = 0, sigma_period_s = 0;
  // loading_and_peaks: the measured peaks compared (the first six: five cycles) and the scale of
  // their pairing with the model's.
  std::size_t peaks_compared = 0;
  PeakPairingScale pairing;
};

MeasuredShape measured_shape(const Scene& scene, const MeasuredForce& f, const FitNoise& noise) {
  MeasuredShape m;
  const double Q_max = *std::max_element(f.Q_N.begin(), f.Q_N.end());
  const double sigma_Q = noise.force * Q_max;
  m.min_drop = scene.output.peak_min_drop;
  m.floor_N = 5.0 * sigma_Q;
  m.min_peak_N = 0.5 * Q_max;
  m.cycles = sampled_cycles(f.t_s, f.Q_N, m.min_drop, m.floor_N, 5, m.min_peak_N);
  m.loading_end = f.t_s.size();
  if (!m.cycles.peaks.empty()) {
    const double t_first = m.cycles.peaks.front().t_max;
    m.loading_end = static_cast<std::size_t>(std::upper_bound(f.t_s.begin(), f.t_s.end(), t_first) - f.t_s.begin());
  }
  const SampledCycles& c = m.cycles;
  if (c.n_drops > 0) {
    const double dt = (f.t_s.back() - f.t_s.front()) / static_cast<double>(f.t_s.size() - 1);
    // How fast Q rises into a peak: the reloading (drop per period), else the first loading.
    const double rise = c.n_periods > 0 ? c.mean_drop / c.mean_period : c.peaks.front().Q_max / c.peaks.front().t_max;
    const double miss = rise * dt;  // how far a sampled maximum may sit below the true one
    // One drop: two sampled extrema, each with force noise and the sampled maximum's miss.
    const double sigma_one_drop_N = std::sqrt(2.0 * sigma_Q * sigma_Q + miss * miss / 6.0);
    m.sigma_drop_N = sigma_one_drop_N / std::sqrt(static_cast<double>(c.n_drops));
    if (c.n_periods > 0) m.sigma_period_s = dt / (std::sqrt(3.0) * c.n_periods);
    // One peak each: its drop as one of the means' n_d, its t_cross uniform within its sampling
    // interval on either curve (σ = dt/√12 each, dt/√6 their difference). Compared up to midway
    // to the first peak left out (else the window's end), faded over half a measured period.
    constexpr std::size_t compared = 6;
    m.peaks_compared = std::min(c.peaks.size(), compared);
    m.pairing.sigma_t_s = dt / std::sqrt(6.0);
    m.pairing.sigma_drop_N = sigma_one_drop_N;
    m.pairing.t_window_s =
        c.peaks.size() > compared ? 0.5 * (c.peaks[compared - 1].t_cross + c.peaks[compared].t_cross) : f.t_s.back();
    m.pairing.taper_s = c.n_periods > 0 ? 0.5 * c.mean_period : dt;
  }
  return m;
}

double relative_square(double model, double measured, double noise) {
  const double r = (model / measured - 1.0) / noise;
  return r * r;
}

// The score applied to an experiment: auto resolved by its measured Q(t).
ForceScore applied_score(ForceScore score, const MeasuredShape& m) {
  if (score != ForceScore::automatic) return score;
  return m.cycles.n_periods >= 2 ? ForceScore::loading_and_cycles : ForceScore::pointwise;
}

// Mean drop of the model's first n peaks, each to its lowest sample so far (0 without a peak).
double model_mean_drop(const SampledCycles& c, int n) {
  const std::size_t m = std::min(c.peaks.size(), static_cast<std::size_t>(n));
  double sum = 0;
  for (std::size_t j = 0; j < m; ++j) sum += c.peaks[j].Q_max - c.peaks[j].Q_min;
  return m > 0 ? sum / static_cast<double>(m) : 0.0;
}

// Mean of the model's first n periods between peaks (0 without one), as sampled_cycles averages them.
double model_mean_period(const SampledCycles& c, int n) {
  const std::size_t m = c.peaks.empty() ? 0 : std::min(c.peaks.size() - 1, static_cast<std::size_t>(n));
  double sum = 0;
  for (std::size_t j = 0; j < m; ++j) sum += c.peaks[j + 1].t_cross - c.peaks[j].t_cross;
  return m > 0 ? sum / static_cast<double>(m) : 0.0;
}

}  // namespace

int area_and_force_count(const Scene& scene, const FitExperiment& fe, const FitNoise& noise, ForceScore score) {
  int n = 0;
  if (scene.experiment.measured) n += static_cast<int>(scene.experiment.measured->Q_N.size());
  if (fe.force && !fe.force->t_s.empty()) {
    const MeasuredShape m = measured_shape(scene, *fe.force, noise);
    if (applied_score(score, m) == ForceScore::pointwise) {
      n += static_cast<int>(fe.force->t_s.size());
    } else {
      n += static_cast<int>(m.loading_end);
      if (applied_score(score, m) == ForceScore::loading_and_peaks) {
        n += 2 * static_cast<int>(m.peaks_compared);
      } else {
        n += (m.cycles.n_drops > 0 ? 1 : 0) + (m.cycles.n_periods > 0 ? 1 : 0);
      }
    }
  }
  if (fe.has_target()) n += 2;
  return n;
}

JointTerms area_and_force_terms(const Scene& scene, const Observables& obs, const std::vector<Sample>& loading,
                                const std::vector<Sample>& series, const FitExperiment& fe, const FitNoise& noise,
                                ForceScore score) {
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
    std::size_t end = Q.size();
    const MeasuredShape m = measured_shape(scene, f, noise);
    t.score = applied_score(score, m);
    // loading_and_cycles: the model's curve read by the measured curve's estimator (its peaks do
    // not depend on how many the means take), held at its first peak after that peak's instant
    // (the same reading as the measured peak's, so the truth scores only the noise).
    double t_hold = std::numeric_limits<double>::infinity(), Q_hold = 0;
    if (t.score == ForceScore::loading_and_cycles || t.score == ForceScore::loading_and_peaks) {
      end = m.loading_end;
      const SampledCycles& mc = m.cycles;
      const SampledCycles model = sampled_cycles(f.t_s, Q, m.min_drop, m.floor_N, 1, m.min_peak_N);
      if (!model.peaks.empty()) t_hold = model.peaks.front().t_max, Q_hold = model.peaks.front().Q_max;
      if (t.score == ForceScore::loading_and_peaks) {
        if (m.peaks_compared > 0) {
          t.cycles = pair_peaks(std::span(mc.peaks).first(m.peaks_compared), model.peaks, m.pairing).chi2;
          t.n_cycles = 2 * static_cast<int>(m.peaks_compared);
        }
      } else if (mc.n_drops > 0) {  // over as many drops and periods as the measured curve shows
        const double rd = (model_mean_drop(model, mc.n_drops) - mc.mean_drop) / m.sigma_drop_N;
        t.cycles += rd * rd;
        t.n_cycles = 1;
        if (mc.n_periods > 0) {
          const double rp = (model_mean_period(model, mc.n_periods) - mc.mean_period) / m.sigma_period_s;
          t.cycles += rp * rp;
          t.n_cycles = 2;
        }
      }
    }
    for (std::size_t k = 0; k < end; ++k) {
      const double q = f.t_s[k] > t_hold ? Q_hold : Q[k];
      const double r = (q - f.Q_N[k]) / scale;
      t.force += r * r;
    }
    t.n_force = static_cast<int>(end);
  }
  if (fe.has_target()) {
    const bool has = obs.ss_cycles > 0;
    t.stick_slip = relative_square(has ? obs.ss_drop : 0.0, fe.target.drop_N, noise.stick_slip) +
                   relative_square(has ? obs.ss_period : 0.0, fe.target.period_s, noise.stick_slip);
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
    case FitObjective::user:
      break;  // the caller's term (fit_problem.cpp)
  }
  return Observables::nan;
}

}  // namespace asperity
