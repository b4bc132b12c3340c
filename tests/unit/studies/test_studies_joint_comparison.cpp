// The interaction study's comparison of the joint calibrations (studies/joint_comparison): the
// Q(t) misfit against a closed form, the noise's 95 % rms against the exact χ² quantiles
// (scipy.stats.chi2.ppf(0.95, n)), the rms's spread against a Monte Carlo over the noise, and
// the reading of a fit.yaml.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "studies/joint_comparison.hpp"
#include "support_files.hpp"

using namespace asperity;
using namespace asperity::testing;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("the Q(t) misfit of a linear model against samples offset by +-d is d", "[joint_comparison]") {
  std::vector<Sample> series;  // Q = 0.5 t on [0, 2], every 0.1 s: interpolation is exact
  for (int i = 0; i <= 20; ++i) {
    Sample s;
    s.t = 0.1 * i;
    s.Q = 0.5 * s.t;
    series.push_back(s);
  }
  MeasuredForce m;
  const double d = 3e-3;
  for (int k = 0; k < 40; ++k) {
    m.t_s.push_back(0.025 + 0.05 * k);  // between the samples
    m.Q_N.push_back(0.5 * m.t_s.back() + (k % 2 ? d : -d));
  }
  const ForceMisfit f = force_misfit(series, m, 0.002);
  CHECK(f.n == 40);
  CHECK_THAT(f.rms, WithinRel(d, 1e-12));
  CHECK_THAT(f.noise, WithinRel(0.002 * (0.5 * m.t_s.back() + d), 1e-12));  // noise · max measured Q
  CHECK_THAT(f.noise_p95, WithinRel(noise_rms_p95(f.noise, 40), 1e-15));
  CHECK_FALSE(f.within_noise());  // d = 3 mN against a noise of 2 mN
  // Beyond the run's end the model's last Q holds (as in the fit's objective).
  m.t_s.push_back(2.5);
  m.Q_N.push_back(1.0);
  const ForceMisfit g = force_misfit(series, m, 0.002);
  CHECK(g.n == 41);
  CHECK_THAT(g.rms, WithinRel(std::sqrt((40 * d * d) / 41), 1e-12));  // the last residual is 1.0 − 1.0 = 0
  CHECK(std::isnan(force_misfit({}, m, 0.002).rms));                  // no series: no number
}

TEST_CASE("the noise's 95 % rms follows the chi-square quantile", "[joint_comparison]") {
  // χ²_{n, 0.95} from scipy.stats.chi2.ppf(0.95, n): the rms of n values of sd 1 stays below
  // sqrt(q/n) in 95 % of cases. Boost.Math's quantile agrees to the printed digits.
  const struct {
    int n;
    double q, tol;
  } cases[] = {{10, 18.307038053275146, 1e-13},
               {100, 124.34211340400407, 1e-13},
               {294, 334.9898387219035, 1e-13},
               {1000, 1074.679448803441, 1e-13}};
  for (const auto& c : cases) {
    INFO("n = " << c.n);
    CHECK_THAT(noise_rms_p95(2.0, c.n), WithinRel(2.0 * std::sqrt(c.q / c.n), c.tol));
  }
  CHECK(std::isnan(noise_rms_p95(1.0, 0)));
}

namespace {
// Portable normal deviates: Box–Muller on the top 53 bits of std::mt19937_64.
struct Normal {
  std::mt19937_64 g;
  explicit Normal(std::uint64_t seed) : g(seed) {}
  double u() { return (static_cast<double>(g() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() { return std::sqrt(-2 * std::log(u())) * std::cos(2 * M_PI * u()); }
};
}  // namespace

TEST_CASE("the rms misfit's spread matches a Monte Carlo over the noise", "[joint_comparison]") {
  const int n = 300;
  const double sigma = 2e-3;
  for (const double a : {0.0, 3e-3}) {  // noise alone; a misfit 1.5 times the noise
    INFO("a = " << a);
    std::vector<double> d(n);
    double d2 = 0;
    for (int k = 0; k < n; ++k) d[k] = a * std::sin(0.37 * k), d2 += d[k] * d[k];
    Normal z(20261125);
    const int draws = 4000;
    double s = 0, s2 = 0;
    for (int i = 0; i < draws; ++i) {
      double q = 0;
      for (int k = 0; k < n; ++k) {
        const double r = d[k] + sigma * z();
        q += r * r;
      }
      const double R = std::sqrt(q / n);
      s += R, s2 += R * R;
    }
    const double mean = s / draws, sd = std::sqrt(s2 / draws - mean * mean);
    const double R_true = std::sqrt(d2 / n + sigma * sigma);  // the expected rms
    // Measured (this seed): the formula's spread 0.95 % (a = 0) and 0.87 % (a = 3e-3) from the
    // Monte Carlo's (itself ±1.1 % from 4,000 draws).
    CHECK_THAT(rms_spread(R_true, sigma, n), WithinRel(sd, 0.03));
  }
  CHECK_THAT(rms_spread(1.0, 1.0, 50), WithinRel(1.0 / std::sqrt(100.0), 1e-14));  // d = 0: σ / sqrt(2n)
}

TEST_CASE("joint fits are read from fit.yaml: the first ok fit of a load kept, a failed one only without it",
          "[joint_comparison]") {
  const auto dir = fresh_dir("joint_comparison");
  const auto a = write_text(dir / "a" / "fit.yaml", R"(fit_file: "fits/a.yaml"
fits:
  - label: "P1"
    status: ok
    objective: 500.5
    parameters:
      "model.alpha_b": {value: 6.5e-16, start: 6e-16, lo: 1e-16, hi: 5e-15, scale: log, at_bound: false}
      "model.epsilon": {value: 0.5, start: 0.8, lo: 0.5, hi: 0.99, scale: linear, at_bound: true}
    runs:
      "P1":
        chi2: {area: 300.25, n_area: 60, force: 200.25, n_force: 294, stick_slip: 0, n_stick_slip: 0}
    uncertainty:
      reduced_chi2: 1.4
      parameters:
        "model.alpha_b": {value: 6.5e-16, sigma: 1e-18, interval95: [6.4804e-16, 6.5196e-16], profile_sigma: 2e-18}
  - label: "P2"
    status: failed
    failure: "evaluation 4: solver stopped"
  - label: "P4"
    status: failed
    failure: "evaluation 2: solver stopped"
)");
  const auto b = write_text(dir / "b" / "fit.yaml", R"(fit_file: "fits/b.yaml"
fits:
  - label: "P1"
    status: ok
    objective: 1
    parameters: {"model.alpha_b": {value: 1e-15}}
  - label: "P3"
    status: ok
    objective: 2
    parameters: {"model.alpha_b": {value: 2e-15}}
    uncertainty:
      reduced_chi2: 3
      failure: "not positive definite"
  - label: "P4"
    status: ok
    objective: 4
    parameters: {"model.alpha_b": {value: 4e-15}}
)");
  const auto fits = read_joint_fits({a, dir / "absent" / "fit.yaml", b});
  REQUIRE(fits.size() == 4);  // P1 (a's, not b's), P2 (failed, in a only), P3 (b), P4 (b's ok over a's failed)
  const JointFitEntry& p1 = fits.at("P1");
  CHECK(p1.status == "ok");
  CHECK(p1.failure.empty());
  CHECK(p1.fit_yaml == a);
  CHECK(p1.fit_file == "fits/a.yaml");
  CHECK(p1.objective == 500.5);
  CHECK(p1.parameters.at("model.alpha_b").value == 6.5e-16);
  CHECK(p1.parameters.at("model.alpha_b").lo95 == 6.4804e-16);
  CHECK(p1.parameters.at("model.alpha_b").hi95 == 6.5196e-16);
  CHECK(p1.parameters.at("model.alpha_b").profile_sigma == 2e-18);
  CHECK(p1.parameters.at("model.epsilon").at_bound);
  CHECK(std::isnan(p1.parameters.at("model.epsilon").sigma));
  CHECK(p1.chi2_force == 200.25);
  CHECK(p1.n_force == 294);
  CHECK(p1.reduced_chi2 == 1.4);
  const JointFitEntry& p3 = fits.at("P3");
  CHECK(p3.fit_file == "fits/b.yaml");
  CHECK(p3.reduced_chi2 == 3);
  CHECK(std::isnan(p3.parameters.at("model.alpha_b").lo95));
  CHECK(p3.n_force == 0);
  CHECK(p3.failure == "not positive definite");  // the Hessian's
  CHECK(fits.at("P2").status == "failed");
  CHECK(fits.at("P2").failure == "evaluation 4: solver stopped");
  CHECK(fits.at("P4").status == "ok");
  CHECK(fits.at("P4").parameters.at("model.alpha_b").value == 4e-15);
  std::filesystem::remove_all(dir);
}
