// Stick-slip cycles of a sampled Q(t) (observe/sampled_cycles.hpp) against closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "observe/sampled_cycles.hpp"

using namespace asperity;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("sampled_cycles: a sampled sine gives its period and its peak-to-trough drop", "[observe][stick_slip]") {
  // Q = c + a sin(2π t / T) sampled every dt with T not a multiple of dt. Crossings of one level
  // by a periodic curve are exactly T apart; linear interpolation between samples misplaces each
  // by at most (curvature · dt²)/(8 · slope) = π² dt² / (4 T) at the level c + a − 0.1 c (relative
  // to T: ~ (π dt / T)²). The sampled extremes sit below the true ones by at most a (π dt / T)²/2.
  const double c = 1.0, a = 0.2, T = 0.137, dt = 0.002;
  std::vector<double> t, Q;
  for (int k = 0; k * dt <= 8 * T; ++k) {
    t.push_back(k * dt);
    Q.push_back(c + a * std::sin(2 * kPi * t.back() / T));
  }
  const SampledCycles s = sampled_cycles(t, Q, 0.02, 0.0, 5);
  REQUIRE(s.n_drops == 5);
  REQUIRE(s.n_periods == 5);
  const double h = std::pow(kPi * dt / T, 2);  // 2.1e-3
  CHECK(std::abs(s.mean_period / T - 1) < h);
  CHECK(std::abs(s.mean_drop - 2 * a) <= a * h);
  CHECK(s.peaks.front().Q_max <= c + a);
  CHECK(s.peaks.front().Q_max > c + a - a * h / 2);
}

TEST_CASE("sampled_cycles: a sawtooth's drop, period and first peak; noise under the floor makes no peak",
          "[observe][stick_slip]") {
  // Linear loading at rate r from q0 to q1, then an instantaneous drop back to q0: period
  // T = (q1 − q0)/r, drop q1 − q0 less at most one sample's rise r dt (the maximum is sampled).
  const double r = 1.0, q0 = 0.8, q1 = 1.0, T = (q1 - q0) / r, dt = 0.003;
  std::vector<double> t, Q;
  for (int k = 0; k * dt <= 7 * T; ++k) {
    t.push_back(k * dt);
    Q.push_back(q0 + r * std::fmod(t.back(), T));
  }
  const SampledCycles s = sampled_cycles(t, Q, 0.05, 0.0, 5);
  REQUIRE(s.n_drops == 5);
  REQUIRE(s.n_periods == 5);
  CHECK(s.mean_drop <= q1 - q0 + 1e-12);
  CHECK(s.mean_drop >= q1 - q0 - 2 * r * dt);
  // Each drop is timed within its sampling interval: the mean of five periods within 2 dt / 5.
  CHECK(std::abs(s.mean_period - T) <= 2 * dt / 5 + 1e-12);
  CHECK(s.peaks.front().t_max <= T);
  CHECK(s.peaks.front().t_max > T - dt);

  // Cut in the second slip: the first drop with its trough, no period.
  const std::size_t cut = static_cast<std::size_t>(1.5 * T / dt);
  const SampledCycles first = sampled_cycles(std::span(t).first(cut), std::span(Q).first(cut), 0.05, 0.0, 5);
  CHECK(first.n_drops == 1);
  CHECK(first.n_periods == 0);
  CHECK(std::isnan(first.mean_period));
  CHECK(first.mean_drop == Approx(s.peaks.front().Q_max - s.peaks.front().Q_min));

  // A ramp with alternating ±σ noise: without a floor each down-step of 2σ > min_drop · Q would
  // count; with a floor of 5σ none does.
  const double sigma = 0.01;
  std::vector<double> tn, Qn;
  for (int k = 0; k < 200; ++k) {
    tn.push_back(k * 0.01);
    Qn.push_back(0.1 + 0.001 * k + (k % 2 ? sigma : -sigma));
  }
  CHECK(!sampled_cycles(tn, Qn, 0.02, 0.0).peaks.empty());
  CHECK(sampled_cycles(tn, Qn, 0.02, 5 * sigma).peaks.empty());
  // A value that is not finite: no peaks rather than a wrong count.
  Q[10] = std::nan("");
  CHECK(sampled_cycles(t, Q, 0.05, 0.0).peaks.empty());

  // Start-up ringing (falls of 0.02 N at Q ≈ 0) then a ramp to 1 N and a drop: peaks only from
  // min_peak_N on.
  std::vector<double> tr, Qr;
  for (int k = 0; k < 120; ++k) {
    tr.push_back(k * 0.01);
    Qr.push_back(k < 10 ? 0.02 * (k % 2) : (k < 110 ? 0.01 * (k - 10) : 0.5));
  }
  CHECK(sampled_cycles(tr, Qr, 0.02, 0.005).peaks.size() > 1);
  const SampledCycles rung = sampled_cycles(tr, Qr, 0.02, 0.005, 5, 0.5);
  REQUIRE(rung.peaks.size() == 1);
  CHECK(rung.peaks.front().Q_max == Approx(0.99));
}
