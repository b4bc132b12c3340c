// Objective pieces against closed forms; failure handling of a fit.
#include <catch2/catch.hpp>
#include <cmath>

#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "fit/objective.hpp"
#include "fit_support.hpp"

using namespace asperity;
using namespace asperity::testing;

TEST_CASE("model_area_at interpolates the monotone loading branch", "[fit][objective]") {
  // A = A0 − c Q on a branch with a ringing back-step (Q decreasing) that must be ignored.
  const double A0 = 1e-6, c = 1e-7;
  std::vector<Sample> branch;
  for (double Q : {0.0, 0.1, 0.2, 0.15, 0.3, 0.4}) {
    Sample s;
    s.Q = Q;
    s.A = (Q == 0.15) ? 0.5e-6 : A0 - c * Q;  // the back-step has a wild area
    branch.push_back(s);
  }
  const double Q_s = 0.45, A_s = A0 - c * 0.45;
  const std::vector<double> Q{0.0, 0.05, 0.25, 0.42, 0.6};
  const std::vector<double> A = model_area_at(branch, Q_s, A_s, Q);
  CHECK(A[0] == Approx(A0).epsilon(1e-14));
  CHECK(A[1] == Approx(A0 - c * 0.05).epsilon(1e-14));
  CHECK(A[2] == Approx(A0 - c * 0.25).epsilon(1e-14));  // between 0.2 and 0.3: linear, exact
  CHECK(A[3] == Approx(A0 - c * 0.42).epsilon(1e-14));  // between the last sample and the peak
  CHECK(A[4] == A_s);                                   // beyond the peak: slid, area A_s
}

TEST_CASE("stick_slip objective counts a run without stick-slip as zero drop and period", "[fit][objective]") {
  Scene s;
  Observables o;
  o.ss_cycles = 0;
  CHECK(experiment_residual(FitObjective::stick_slip, s, o, {}, {0.1, 0.2}) == 2.0);
  o.ss_cycles = 3;
  o.ss_drop = 0.15;
  o.ss_period = 0.1;
  CHECK(experiment_residual(FitObjective::stick_slip, s, o, {}, {0.1, 0.2}) == Approx(0.25 + 0.25));
}

TEST_CASE("model_force_at interpolates Q(t) linearly; area_and_force terms are chi-squares in noise units",
          "[fit][objective]") {
  // Q(t) = 2 t + 1 sampled every 0.1 s on [0, 1]: linear interpolation is exact inside, the
  // end samples hold outside.
  std::vector<Sample> series;
  for (int k = 0; k <= 10; ++k) {
    Sample s;
    s.t = 0.1 * k;
    s.Q = 2 * s.t + 1;
    series.push_back(s);
  }
  const std::vector<double> t{-0.5, 0.0, 0.05, 0.333, 1.0, 2.0};
  const std::vector<double> Q = model_force_at(series, t);
  CHECK(Q[0] == 1.0);
  CHECK(Q[1] == 1.0);
  CHECK(Q[2] == Approx(1.1).epsilon(1e-14));
  CHECK(Q[3] == Approx(1.666).epsilon(1e-14));
  CHECK(Q[4] == Approx(3.0).epsilon(1e-14));
  CHECK(Q[5] == Approx(3.0).epsilon(1e-14));
  // Force term: measured = model + d_k, noise level 0.01 of max Q (3.0): chi2 = Σ (d_k/0.03)².
  FitExperiment fe;
  fe.force = MeasuredForce{{0.0, 0.5, 1.0}, {1.0 + 0.03, 2.0 - 0.06, 3.0}};
  Scene scene;
  scene.experiment.measured = MeasuredCurve{{0.0, 1.0}, {1e-6 + 2e-9, 0.9e-6}};  // A0 = 1e-6
  Observables obs;
  obs.A0 = 1e-6;
  obs.Q_s = 1.0;
  obs.A_s = 0.9e-6;
  std::vector<Sample> loading(2);
  loading[0].Q = 0, loading[0].A = 1e-6;
  loading[1].Q = 1, loading[1].A = 0.9e-6;
  FitNoise noise;
  noise.area = 0.001;  // 1e-9 m²
  noise.force = 0.01;
  fe.target = {0.1, 0.2};
  obs.ss_cycles = 2, obs.ss_drop = 0.11, obs.ss_period = 0.2;
  noise.stick_slip = 0.05;
  const JointTerms j = area_and_force_terms(scene, obs, loading, series, fe, noise, ForceScore::pointwise);
  // force: largest measured Q 3.0, scale 0.03: (0.03/0.03)² + (0.06/0.03)² + 0 = 5
  CHECK(j.force == Approx(5.0).epsilon(1e-12));
  CHECK(j.n_force == 3);
  CHECK(j.area == Approx(4.0).epsilon(1e-9));  // (2e-9 / 1e-9)², 0
  CHECK(j.n_area == 2);
  CHECK(j.stick_slip == Approx(4.0).epsilon(1e-9));  // ((0.11/0.1 − 1)/0.05)² + 0
  CHECK(j.n_stick_slip == 2);
  CHECK(j.total() == Approx(j.area + j.force + j.stick_slip));
  CHECK(area_and_force_count(scene, fe, {}, ForceScore::pointwise) == 7);
}

TEST_CASE("Scaled coordinates map exactly onto the bounds", "[fit][objective]") {
  FitParameter lin{"model.p", 1.0, 2.0, 1.5, false, false};
  FitParameter lg{"model.alpha_b", 1e-16, 5e-15, 7e-16, true, false};
  for (const FitParameter& p : {lin, lg}) {
    CHECK(parameter_value(p, 0.0) == p.lo);
    CHECK(parameter_value(p, 1.0) == p.hi);
    CHECK(parameter_value(p, -0.5) == p.lo);
    CHECK(parameter_value(p, 1.5) == p.hi);
    CHECK(parameter_value(p, parameter_coordinate(p, p.start)) == Approx(p.start).epsilon(1e-14));
  }
  CHECK(parameter_value(lg, 0.5) == Approx(std::sqrt(1e-16 * 5e-15)).epsilon(1e-14));  // geometric midpoint
}

TEST_CASE("A NaN objective ends the fit with a clear reason", "[fit][objective]") {
  // stop.time 1e-6 s: the loading branch holds only Q = 0, so the model's alpha is NaN.
  const FitCase c = make_fit_case("nan", 0.725e-15, 1.5, 0.1, 40);
  const auto f = write_text(c.dir / "fit.yaml",
                            "objective: quadratic_alpha\n"
                            "experiments: [{scene: scene.yaml, set: {stop.time: 1.0e-6}}]\n"
                            "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 7e-16}}\n");
  const FitResult r = asperity::testing::run_fit_serial(f);
  const Optimization& o = r.fits[0];
  CHECK_FALSE(o.ok());
  CHECK(o.stop_reason == "FORCED_STOP");
  CHECK(o.evaluations == 1);
  CHECK(o.failure.find("NaN") != std::string::npos);
  CHECK(o.failure.find("fit-nan") != std::string::npos);  // names the experiment
  CHECK(std::isnan(o.objective));
  std::filesystem::remove_all(c.dir);
}

TEST_CASE("loading_and_cycles scores the loading branch held at the peak, and the cycles by drop and period",
          "[fit][objective]") {
  // Measured: a sawtooth rising at 1 N/s from 0, dropping to 0 every 1 s, sampled every 0.01 s
  // for 5.5 s. Its first peak is the sample t = 0.99 s: the loading branch is 100 samples.
  FitExperiment fe;
  MeasuredForce f;
  for (int k = 0; k <= 550; ++k) {
    f.t_s.push_back(0.01 * k);
    f.Q_N.push_back(0.01 * (k % 100));
  }
  fe.force = f;
  Scene scene;  // no measured A(Q); output.peak_min_drop 0.02
  FitNoise noise;
  noise.force = 0.01;  // residual unit: 0.01 · max Q (0.99)
  noise.stick_slip = 0.05;
  const double scale = 0.01 * 0.99;

  // The model, every 0.001 s: the same loading to its static peak at t = 0.8 s, then drops of
  // 0.5 N every 0.5 s (rising from 0.3 N at 1 N/s). Read at the measured instants its first
  // peak is the sample t = 0.79 s, Q = 0.79 N (its Observables play no part).
  std::vector<Sample> series;
  for (int k = 0; k <= 5500; ++k) {
    Sample s;
    s.t = 0.001 * k;
    s.Q = k < 800 ? 0.001 * k : 0.3 + 0.001 * ((k - 800) % 500);
    series.push_back(s);
  }
  Observables obs;
  obs.peak_found = true;
  obs.t_peak = 0.7995;
  obs.Q_s = 0.7995;
  const JointTerms p = area_and_force_terms(scene, obs, {}, series, fe, noise, ForceScore::loading_and_cycles);
  REQUIRE(p.n_force == 100);
  REQUIRE(p.n_cycles == 2);
  // Held at 0.79 N past t = 0.79 s: the samples t = 0.80 … 0.99 miss by t − 0.79 (closed form).
  double expect = 0;
  for (int k = 80; k <= 99; ++k) expect += std::pow((0.01 * k - 0.79) / scale, 2);
  CHECK(p.force == Approx(expect).epsilon(1e-9));
  // Cycles, both read at the measured instants over the measured 5 drops and 4 periods:
  // measured drop 0.99 N and period 1 s; the model's sampled drop 0.79 − 0.3 = 0.49 N and
  // period 0.5 s. Deviations (objective.hpp): σ_Q = 0.0099 N, reloading 0.99 N/s, dt 0.01 s.
  const double sigma_Q = 0.0099, miss = 0.99 * 0.01;
  const double sigma_drop = std::sqrt((2 * sigma_Q * sigma_Q + miss * miss / 6) / 5),
               sigma_period = 0.01 / (std::sqrt(3.0) * 4);
  CHECK(p.cycles == Approx(std::pow(0.5 / sigma_drop, 2) + std::pow(0.5 / sigma_period, 2)).epsilon(1e-6));
  CHECK(area_and_force_count(scene, fe, noise, ForceScore::loading_and_cycles) == 102);
  // Pointwise scores all 551 samples; the measured curve scored against itself is 0 either way.
  CHECK(area_and_force_terms(scene, obs, {}, series, fe, noise, ForceScore::pointwise).n_force == 551);
  std::vector<Sample> same;
  for (std::size_t k = 0; k < f.t_s.size(); ++k) {
    Sample s;
    s.t = f.t_s[k];
    s.Q = f.Q_N[k];
    same.push_back(s);
  }
  obs.t_peak = 0.99, obs.Q_s = 0.99;
  const JointTerms z = area_and_force_terms(scene, obs, {}, same, fe, noise, ForceScore::loading_and_cycles);
  CHECK(z.force == Approx(0.0).margin(1e-20));
  CHECK(z.cycles == Approx(0.0).margin(1e-20));
  // auto: loading_and_cycles here (four complete cycles measured); pointwise on a window that
  // ends before the third peak (one complete cycle).
  const JointTerms au = area_and_force_terms(scene, obs, {}, series, fe, noise, ForceScore::automatic);
  CHECK(au.score == ForceScore::loading_and_cycles);
  CHECK(au.n_force == 100);
  CHECK(au.n_cycles == 2);
  FitExperiment short_fe;
  short_fe.force = MeasuredForce{std::vector<double>(f.t_s.begin(), f.t_s.begin() + 250),
                                 std::vector<double>(f.Q_N.begin(), f.Q_N.begin() + 250)};
  const JointTerms a = area_and_force_terms(scene, obs, {}, series, short_fe, noise, ForceScore::automatic);
  CHECK(a.score == ForceScore::pointwise);
  CHECK(a.n_force == 250);
  CHECK(a.n_cycles == 0);
  CHECK(area_and_force_count(scene, short_fe, noise, ForceScore::automatic) == 250);
  // A model without stick-slip counts as drop = period = 0.
  std::vector<Sample> flat = same;
  for (Sample& s : flat) s.Q = std::min(s.t, 0.99);
  CHECK(area_and_force_terms(scene, obs, {}, flat, fe, noise, ForceScore::loading_and_cycles).cycles ==
        Approx(std::pow(0.99 / sigma_drop, 2) + std::pow(1.0 / sigma_period, 2)));

  // loading_and_peaks: the same loading branch; the five measured peaks (t_cross 0.9905 … 4.9905 s,
  // where Q crosses 0.99 − 0.0495) paired by time with the model's (observe/peak_pairing.hpp),
  // two residuals each. Itself: 0. Without a peak: each measured one unpaired at its drop's excess
  // over the fall 5 σ_Q = 0.0495 N, in units of one peak's σ_drop, at full weight (the window's
  // end lies 0.51 s after the last, beyond the taper of half a period).
  CHECK(area_and_force_count(scene, fe, noise, ForceScore::loading_and_peaks) == 110);
  const JointTerms zp = area_and_force_terms(scene, obs, {}, same, fe, noise, ForceScore::loading_and_peaks);
  CHECK(zp.n_force == 100);
  CHECK(zp.n_cycles == 10);
  CHECK(zp.cycles == Approx(0.0).margin(1e-20));
  const double sigma_peak = std::sqrt(2 * sigma_Q * sigma_Q + miss * miss / 6);
  const JointTerms fp = area_and_force_terms(scene, obs, {}, flat, fe, noise, ForceScore::loading_and_peaks);
  CHECK(fp.cycles == Approx(5 * std::pow((0.99 - 0.0495) / sigma_peak, 2)).epsilon(1e-9));
  CHECK(fp.force == Approx(z.force).margin(1e-12));
}
