#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "observe/observables.hpp"

using namespace asperity;

namespace {

Scene scene_with(double A0) {
  Scene s;
  s.experiment.junctions.area_m2 = {A0};
  return s;
}

RunInfo info_with(double A0) {
  RunInfo i;
  i.N = 1;
  i.A0 = A0;
  i.K0 = 100;
  i.T0 = 0.2;
  i.dt = 2e-5;
  i.t_end = 1.5;
  i.max_f_over_sigmaA = 0.99;
  i.max_f_over_sigma_exp_A = 1.1;
  i.stats.steps = 42;
  i.stats.slips = 7;
  return i;
}

// Quadratic loading A = A0 − α Q², Q = t, up to the peak at t = 0.5, then a drop.
// One of two junctions slips at t = 0.3; with_drop: the other slips at 0.55 and the slider
// sticks at t = 0.65.
void feed(Recorder& rec, double A0, double alpha, bool with_drop) {
  for (int i = 0; i <= 100; ++i) {
    if (i == 30) rec.population({0.3, 1, false, 1});
    const double t = 0.01 * i;
    const double Q = t <= 0.5 ? t : 0.5 - 0.5 * (t - 0.5);
    const double A = A0 - alpha * std::min(Q, 0.5) * std::min(Q, 0.5);
    rec.sample({t, 0, 0, Q, A, 0, 1});
    if (with_drop && i == 50) rec.extremum({0.5, 0.5, A, true});
    if (with_drop && i == 60) rec.extremum({0.6, 0.45, A, false});
    if (with_drop && i == 55) rec.population({0.55, 1, false, 0});
    if (with_drop && i == 65) rec.population({0.65, 0, true, 0});
  }
}

}  // namespace

TEST_CASE("summarize: peak, quadratic fit on the loading branch, solver info", "[observe]") {
  const double A0 = 1e-5, alpha = 4e-6;
  Recorder rec(0.01, false, 1e-3, false, -1);
  feed(rec, A0, alpha, true);
  const Observables o = summarize(scene_with(A0), info_with(A0), rec, 3.5);
  CHECK(o.peak_found);
  CHECK(o.peak_rule == PeakRule::stick);
  CHECK(o.Q_s == 0.5);
  CHECK(o.t_peak == 0.5);
  CHECK(o.A_s == Approx(A0 - alpha * 0.25).epsilon(1e-14));
  CHECK(o.area_drop_fraction == Approx(alpha * 0.25 / A0).epsilon(1e-14));
  CHECK(o.alpha_points == 51);  // samples t = 0 … 0.5
  CHECK(o.alpha == Approx(alpha).epsilon(1e-14));
  CHECK(o.alpha_R2 == Approx(1.0).epsilon(1e-14));
  CHECK(o.shape_exponent == Approx(2.0).epsilon(3e-14));
  CHECK(o.ss_cycles == 0);
  CHECK(std::isnan(o.ss_drop));
  CHECK(o.n_peaks == 1);
  CHECK(o.steps == 42);
  CHECK(o.slips == 7);
  CHECK(o.max_f_over_sigmaA == 0.99);
  CHECK(o.wall_s == 3.5);
  CHECK(std::isnan(o.alpha_measured));
}

TEST_CASE("summarize without a peak uses the highest Q after the first slip and cuts the fit there", "[observe]") {
  const double A0 = 1e-5, alpha = 4e-6;
  Recorder rec(0.01, false, 1e-3, false, -1);
  feed(rec, A0, alpha, false);  // the drop after t = 0.5 is never reported as extrema
  Scene s = scene_with(A0);
  MeasuredCurve m;
  for (int i = 0; i <= 10; ++i) {
    m.Q_N.push_back(0.05 * i);
    m.A_m2.push_back(A0 - 2 * alpha * m.Q_N.back() * m.Q_N.back());
  }
  s.experiment.measured = m;
  const Observables o = summarize(s, info_with(A0), rec, 0);
  CHECK_FALSE(o.peak_found);
  CHECK(o.peak_rule == PeakRule::none);
  CHECK(o.Q_s == 0.5);
  CHECK(o.t_peak == Approx(0.5).epsilon(1e-14));
  CHECK(o.alpha_points == 51);
  CHECK(o.alpha == Approx(alpha).epsilon(1e-14));
  CHECK(o.alpha_measured == Approx(2 * alpha).epsilon(1e-14));
  CHECK(o.alpha_measured_R2 == Approx(1.0).epsilon(1e-14));
  CHECK(o.shape_exponent_measured == Approx(2.0).epsilon(2e-14));
}
