#include "observe/shape_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "observe/quadratic_fit.hpp"
#include "scene/scene.hpp"

namespace asperity {
namespace {

double rms(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x * x;
  return v.empty() ? NAN : std::sqrt(s / static_cast<double>(v.size()));
}

double sd(const std::vector<double>& v) {
  std::vector<double> f;
  for (const double x : v)
    if (std::isfinite(x)) f.push_back(x);
  if (f.size() < 2) return NAN;
  double m = 0;
  for (const double x : f) m += x;
  m /= static_cast<double>(f.size());
  double s = 0;
  for (const double x : f) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(f.size() - 1));
}

// A of the loading branch where Q first reaches q (linear between samples); NaN beyond it.
double area_at(const std::vector<Sample>& loading, double q) {
  for (std::size_t k = 0; k < loading.size(); ++k) {
    if (loading[k].Q < q) continue;
    if (k == 0) return loading[0].A;
    const Sample& a = loading[k - 1];
    const Sample& b = loading[k];
    const double w = b.Q > a.Q ? (q - a.Q) / (b.Q - a.Q) : 1.0;
    return a.A + w * (b.A - a.A);
  }
  return NAN;
}

}  // namespace

// The bootstrap; with `model` (A_model at each Q_i) also the spread of the model's residual.
ShapeComparison bootstrap(const std::vector<double>& Q, const std::vector<double>& A, double A0, std::uint64_t seed,
                          std::size_t resamples, const std::vector<double>* model) {
  ShapeComparison c;
  const QuadraticFit fit = fit_quadratic_area(Q, A, A0);
  c.alpha_measured = fit.alpha;
  c.n_measured = fit_power_law(Q, A, A0).n;
  if (!std::isfinite(fit.alpha) || Q.size() < 3) return c;
  std::vector<double> fitted(Q.size()), resid(Q.size());
  for (std::size_t i = 0; i < Q.size(); ++i) {
    fitted[i] = A0 - fit.alpha * Q[i] * Q[i];
    resid[i] = A[i] - fitted[i];
  }
  c.noise_rms = rms(resid);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, Q.size() - 1);
  std::vector<double> alphas, ns, noise, model_rms;
  std::vector<double> star(Q.size()), r(Q.size());
  for (std::size_t b = 0; b < resamples; ++b) {
    for (std::size_t i = 0; i < Q.size(); ++i) star[i] = fitted[i] + resid[pick(rng)];
    const QuadraticFit f = fit_quadratic_area(Q, star, A0);
    alphas.push_back(f.alpha);
    ns.push_back(fit_power_law(Q, star, A0).n);
    for (std::size_t i = 0; i < Q.size(); ++i) r[i] = star[i] - (A0 - f.alpha * Q[i] * Q[i]);
    noise.push_back(rms(r));
    if (model) {
      for (std::size_t i = 0; i < Q.size(); ++i) r[i] = (*model)[i] - star[i];
      model_rms.push_back(rms(r));
    }
  }
  c.resamples = resamples;
  c.residual_rms_sd = model ? sd(model_rms) : NAN;
  c.alpha_measured_sd = sd(alphas);
  c.n_measured_sd = sd(ns);
  if (!noise.empty()) {
    std::sort(noise.begin(), noise.end());
    c.noise_rms_p95 = noise[std::min(
        noise.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(noise.size()))) - 1)];
  }
  return c;
}

ShapeComparison bootstrap_measured(const std::vector<double>& Q, const std::vector<double>& A, double A0,
                                   std::uint64_t seed, std::size_t resamples) {
  return bootstrap(Q, A, A0, seed, resamples, nullptr);
}

ShapeComparison compare_shapes(const std::vector<Sample>& loading, const MeasuredCurve& measured, double A0,
                               std::uint64_t seed, std::size_t resamples) {
  // Only the measured points the model's loading branch reaches (its Q_s may be smaller).
  std::vector<double> Q, A, model, res;
  for (std::size_t i = 0; i < measured.Q_N.size(); ++i) {
    const double am = area_at(loading, measured.Q_N[i]);
    if (!std::isfinite(am) || !std::isfinite(measured.A_m2[i])) continue;
    Q.push_back(measured.Q_N[i]);
    A.push_back(measured.A_m2[i]);
    model.push_back(am);
    res.push_back(am - measured.A_m2[i]);
  }
  ShapeComparison c = bootstrap(Q, A, A0, seed, resamples, &model);
  c.points_used = Q.size();
  c.residual_rms = rms(res);
  c.alpha_model = fit_quadratic_area(loading, A0).alpha;
  c.n_model = fit_power_law(loading, A0).n;
  return c;
}

}  // namespace asperity
