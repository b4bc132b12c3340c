// observe/shape_comparison.hpp: the A(Q) shape measures and their spread over measurement noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "observe/quadratic_fit.hpp"
#include "observe/shape_comparison.hpp"
#include "scene/scene.hpp"

using namespace asperity;

namespace {

// A stand-in-like measured curve: 60 points, Q from 0 to Q_s, A = A0 − α Q² plus Gaussian noise
// of 0.2 % of A0 (docs/model.md §7's recipe).
constexpr double kA0 = 1.4e-5, kAlpha = 3.1e-7, kQs = 3.3, kSigma = 0.002 * kA0;
constexpr int kPoints = 60;

std::vector<double> q_points() {
  std::vector<double> Q(kPoints);
  for (int i = 0; i < kPoints; ++i) Q[static_cast<std::size_t>(i)] = kQs * i / (kPoints - 1.0);
  return Q;
}

std::vector<double> noisy_parabola(const std::vector<double>& Q, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, kSigma);
  std::vector<double> A(Q.size());
  for (std::size_t i = 0; i < Q.size(); ++i) A[i] = kA0 - kAlpha * Q[i] * Q[i] + noise(rng);
  return A;
}

double sd_of(const std::vector<double>& v) {
  double m = 0, s = 0;
  for (const double x : v) m += x;
  m /= static_cast<double>(v.size());
  for (const double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

TEST_CASE("shape bootstrap: the spread of alpha is the residual bootstrap's closed form", "[observe][shape]") {
  // With A0 fixed, α* − α̂ = Σ Q_i² e*_i / Σ Q_i⁴, so its variance over resamples is exactly
  // Var(e*) / Σ Q⁴ (Var over the empirical residuals); B = 4000 resamples estimate it to
  // ~1.1 % (measured 0.4 %).
  const auto Q = q_points();
  std::mt19937_64 rng(1);
  const auto A = noisy_parabola(Q, rng);
  const ShapeComparison c = bootstrap_measured(Q, A, kA0, 7, 4000);
  double q4 = 0, m = 0, m2 = 0;
  for (const double q : Q) q4 += q * q * q * q;
  for (std::size_t i = 0; i < Q.size(); ++i) {
    const double e = A[i] - (kA0 - c.alpha_measured * Q[i] * Q[i]);
    m += e / kPoints;
    m2 += e * e / kPoints;
  }
  const double closed = std::sqrt((m2 - m * m) / q4);
  INFO("bootstrap " << c.alpha_measured_sd << ", closed form " << closed);
  CHECK_THAT(c.alpha_measured_sd, Catch::Matchers::WithinRel(closed, 0.04));
  CHECK(c.resamples == 4000);
  // The same seed gives the same numbers.
  CHECK(bootstrap_measured(Q, A, kA0, 7, 4000).alpha_measured_sd == c.alpha_measured_sd);
}

TEST_CASE("shape bootstrap: its spreads match a Monte Carlo over the noise", "[observe][shape]") {
  // The truth: the sd of α̂ and n̂ over 2,000 independent noisy curves. The bootstrap sees one
  // curve; averaged over 40 curves its estimate must agree (n's estimator is nonlinear at small Q,
  // so its bootstrap is only approximate).
  const auto Q = q_points();
  std::mt19937_64 rng(2);
  std::vector<double> alphas, ns;
  for (int k = 0; k < 2000; ++k) {
    const auto A = noisy_parabola(Q, rng);
    alphas.push_back(fit_quadratic_area(Q, A, kA0).alpha);
    ns.push_back(fit_power_law(Q, A, kA0).n);
  }
  const double mc_alpha = sd_of(alphas), mc_n = sd_of(ns);
  double boot_alpha = 0, boot_n = 0;
  for (int k = 0; k < 40; ++k) {
    const auto A = noisy_parabola(Q, rng);
    const ShapeComparison c = bootstrap_measured(Q, A, kA0, 100 + k, 500);
    boot_alpha += c.alpha_measured_sd / 40;
    boot_n += c.n_measured_sd / 40;
  }
  INFO("alpha sd: Monte Carlo " << mc_alpha << ", bootstrap " << boot_alpha << "; n sd: Monte Carlo " << mc_n
                                << ", bootstrap " << boot_n);
  CHECK_THAT(boot_alpha, Catch::Matchers::WithinRel(mc_alpha, 0.03));  // measured 0.5 %
  CHECK_THAT(boot_n, Catch::Matchers::WithinRel(mc_n, 0.06));          // measured 1.5 %
  // The exponent of an exact parabola with this noise spreads widely: the reason a verdict on
  // n alone cannot be trusted (issue 22).
  CHECK(mc_n > 0.05);
}

TEST_CASE("shape comparison: a parabola model agrees within the noise, a flatter one does not", "[observe][shape]") {
  const auto Q = q_points();
  std::mt19937_64 rng(3);
  MeasuredCurve measured;
  measured.Q_N = Q;
  measured.A_m2 = noisy_parabola(Q, rng);
  // Model loading branches on a fine grid of Q up to 1.02 Q_s: the true parabola, and a curve
  // A0 − c Q^1.3 with the same area at Q_s (the independent model's kind of shape).
  std::vector<Sample> parabola, flatter;
  const double c13 = kAlpha * kQs * kQs / std::pow(kQs, 1.3);
  for (int k = 0; k <= 2000; ++k) {
    Sample s;
    s.Q = 1.02 * kQs * k / 2000.0;
    s.A = kA0 - kAlpha * s.Q * s.Q;
    parabola.push_back(s);
    s.A = kA0 - c13 * std::pow(s.Q, 1.3);
    flatter.push_back(s);
  }
  const ShapeComparison good = compare_shapes(parabola, measured, kA0);
  const ShapeComparison bad = compare_shapes(flatter, measured, kA0);
  CHECK(good.points_used == static_cast<std::size_t>(kPoints));
  CHECK_FALSE(good.alpha_differs());
  CHECK_FALSE(good.residual_exceeds_noise());
  CHECK_THAT(good.alpha_model, Catch::Matchers::WithinRel(kAlpha, 1e-9));  // exact parabola
  CHECK(good.residual_rms < 1.5 * kSigma);                                 // the noise itself
  CHECK(bad.alpha_differs());
  CHECK(bad.residual_exceeds_noise());
  CHECK(bad.residual_rms > 3 * kSigma);
  // The model's residual spreads over the noise like the noise's own rms, about σ/sqrt(2n) = 0.09 σ
  // for the right model (measured 0.087 σ; 0.13 σ for the flatter one), far below the excess.
  INFO("residual sd: parabola " << good.residual_rms_sd / kSigma << " sigma, flatter " << bad.residual_rms_sd / kSigma);
  CHECK(good.residual_rms_sd < 0.2 * kSigma);
  CHECK(bad.residual_rms - good.residual_rms > 5 * (good.residual_rms_sd + bad.residual_rms_sd));
  // Points beyond the model's largest Q are left out (a model with a smaller Q_s).
  std::vector<Sample> short_branch(parabola.begin(), parabola.begin() + 1000);  // up to 0.51 Q_s
  CHECK(compare_shapes(short_branch, measured, kA0).points_used == 31);
}
