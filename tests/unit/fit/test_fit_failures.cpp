// Fits that cannot mean anything fail loudly: a model run without a confirmed peak or an
// objective 0 at every evaluation (status failed, exit 1), a measured A(Q) that does not
// decrease or is not anchored at Σ A0 (exit 2 at the experiment file's `measured:` line, before
// any run).
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "fit_support.hpp"
#include "scene/csv.hpp"

using namespace asperity;
using namespace asperity::testing;
namespace fs = std::filesystem;

namespace {

int asperity_in(const fs::path& work, const std::string& args, std::string* err) {
  const std::string cmd =
      "cd '" + work.string() + "' && '" + ASPERITY_BINARY + "' " + args + " >stdout.txt 2>stderr.txt";
  const int rc = std::system(cmd.c_str());
  *err = slurp(work / "stderr.txt");
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// 1-based line of `key:` at the start of a line of a YAML file (found by reading its text).
int line_of(const fs::path& yaml, const std::string& key) {
  std::istringstream in(slurp(yaml));
  std::string line;
  for (int i = 1; std::getline(in, line); ++i)
    if (line.rfind(key + ":", 0) == 0) return i;
  return -1;
}

const std::string kQuadraticFit =
    "objective: quadratic_alpha\nexperiments: [scene.yaml]\n"
    "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\nprofile: false\n";

// load_fit must refuse the case with `what` in the message, located at experiment.yaml's
// `measured:` line; the CLI exits 2 with that prefix and writes nothing.
void require_refused(const FitCase& c, const std::string& what) {
  const fs::path f = write_text(c.dir / "f.yaml", kQuadraticFit);
  const int line = line_of(c.dir / "experiment.yaml", "measured");
  REQUIRE(line > 0);
  try {
    (void)load_fit(f);
    FAIL("load_fit accepted it");
  } catch (const io::InputError& e) {
    CHECK(e.key == "measured");
    CHECK(e.line == line);
    CHECK(fs::path(e.file).filename() == "experiment.yaml");
    CHECK(e.message.find(what) != std::string::npos);
    CHECK(e.message.find("measured.csv") != std::string::npos);
  }
  std::string err;
  CHECK(asperity_in(c.dir, "fit f.yaml --quiet", &err) == 2);
  INFO(err);
  // One line "FILE:LINE: measured: message", FILE the experiment file.
  const std::string where = "experiment.yaml:" + std::to_string(line) + ": measured: ";
  CHECK(err.find(where) != std::string::npos);
  CHECK(err.find(where) < err.find('\n'));
  CHECK(err.find(c.dir.string()) == 0);
  CHECK(err.find(what) != std::string::npos);
  CHECK_FALSE(fs::exists(c.dir / "results"));
}

}  // namespace

TEST_CASE("A fit whose model runs end before the peak fails, with the reason", "[fit][failures]") {
  const FitCase c = make_fit_case("nopeak", 0.725e-15, 1.5, 0.1, 40);
  // Where the peak is at the fit's start value; the fit then runs to 60 % of that time only.
  const Scene s =
      load_scene(c.dir / "scene.yaml", {"model.alpha_b=1e-15", "stop.at_first_peak=true", "output.series=[]"});
  const Observables full = simulate(s).obs;
  REQUIRE(full.peak_found);
  const double t_stop = 0.6 * full.t_peak;
  const fs::path f = write_text(c.dir / "f.yaml",
                                "objective: quadratic_alpha\n"
                                "experiments: [{scene: scene.yaml, set: {stop.time: " +
                                    io::format_double(t_stop) +
                                    "}}]\n"
                                    "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\n"
                                    "profile: false\n");
  const FitResult r = asperity::testing::run_fit_serial(f);
  const Optimization& o = r.fits[0];
  CHECK_FALSE(o.ok());
  CHECK(o.stop_reason == "FORCED_STOP");
  CHECK(o.failure.find("no confirmed static friction peak") != std::string::npos);
  CHECK(o.failure.find("fit-nopeak") != std::string::npos);       // the experiment
  CHECK(o.failure.find("experiment.yaml") != std::string::npos);  // and its file
  CHECK(o.failure.find("NaN") == std::string::npos);              // not the NaN-objective failure
  // The CLI: exit 1, the results written with status failed.
  std::string err;
  CHECK(asperity_in(c.dir, "fit f.yaml --quiet --out out", &err) == 1);
  CHECK(err.find("no confirmed static friction peak") != std::string::npos);
  const std::string y = slurp(c.dir / "out" / "fit.yaml");
  CHECK(y.find("status: failed") != std::string::npos);
  CHECK(y.find("status: ok") == std::string::npos);
  fs::remove_all(c.dir);
}

TEST_CASE("A fit whose objective is 0 at every evaluation fails: noise levels that underflow every residual",
          "[fit][failures]") {
  const FitCase c = make_fit_case("degenerate", 0.725e-15, 1.5, 0.1, 40);
  MeasuredForce force;
  for (int k = 1; k <= 5; ++k) {
    force.t_s.push_back(0.01 * k);
    force.Q_N.push_back(0.02 * k);
  }
  write_force_csv(c.dir / "force.csv", force, {"a short Q(t) (test_fit_failures.cpp)"});
  const fs::path f =
      write_text(c.dir / "f.yaml",
                 "objective: area_and_force\nexperiments: [{scene: scene.yaml, force: force.csv}]\n"
                 "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\n"
                 "optimizer: {algorithm: LN_BOBYQA, max_evaluations: 4}\nprofile: false\nintervals: false\n");
  FitSpec spec = load_fit(f);
  FitOptions options;
  options.threads = 1;
  options.profile = false;
  options.error_bars = false;
  REQUIRE(run_fit(spec, options).fits[0].ok());  // at sane levels a fit
  // The loader refuses such levels (tests/bad_inputs/fit_noise_1e300.yaml): the run's own guard.
  spec.noise.area = spec.noise.force = 1e300;
  const Optimization o = run_fit(spec, options).fits[0];
  CHECK_FALSE(o.ok());
  CHECK(o.failure.find("the objective is 0 at every one of its") != std::string::npos);
  fs::remove_all(c.dir);
}

TEST_CASE("A measured A(Q) that rises with Q is refused", "[fit][failures]") {
  const FitCase c = make_fit_case("rising", 0.725e-15, 1.5, 0.1, 40);
  MeasuredCurve m = read_measured_csv(c.dir / "measured.csv");
  const double A0 = m.A_m2.front();
  for (double& a : m.A_m2) a = 2 * A0 - a;  // mirrored: rises by the same amount
  write_measured_csv(c.dir / "measured.csv", m);
  require_refused(c, "does not decrease");
  fs::remove_all(c.dir);
}

TEST_CASE("A measured A(Q) in mm² instead of m² is refused", "[fit][failures]") {
  const FitCase c = make_fit_case("mm2", 0.725e-15, 1.5, 0.1, 40);
  MeasuredCurve m = read_measured_csv(c.dir / "measured.csv");
  for (double& a : m.A_m2) a *= 1e6;
  write_measured_csv(c.dir / "measured.csv", m);
  require_refused(c, "x the sum of the junction areas");
  fs::remove_all(c.dir);
}

TEST_CASE("measured_curve_problem: decrease significant against noise, A(0) within 10 % of the sum",
          "[fit][failures]") {
  // Stand-in-like curves: A = A0 (1 − d (Q/Qs)²) + Gaussian noise of 0.2 % of A0, 60 points.
  const double A0 = 4e-6, Qs = 0.75;
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> noise(0.0, 0.002 * A0);
  auto curve = [&](double drop, double offset) {
    MeasuredCurve m;
    for (int i = 0; i < 60; ++i) {
      const double Q = Qs * i / 59.0;
      m.Q_N.push_back(Q);
      m.A_m2.push_back(A0 * (offset - drop * (Q / Qs) * (Q / Qs)) + noise(rng));
    }
    return m;
  };
  CHECK(measured_curve_problem(curve(0.15, 1.0), A0).empty());  // the stand-ins' smallest drop
  CHECK(measured_curve_problem(curve(0.01, 1.0), A0).empty());  // 1 % drop: 5 x the noise, still seen
  CHECK(measured_curve_problem(curve(0.0, 1.0), A0).find("does not decrease") != std::string::npos);
  CHECK(measured_curve_problem(curve(-0.15, 1.0), A0).find("does not decrease") != std::string::npos);
  CHECK(measured_curve_problem(curve(0.15, 1.08), A0).empty());  // 8 % off: accepted
  CHECK(measured_curve_problem(curve(0.15, 1.12), A0).find("sum of the junction areas") != std::string::npos);
  CHECK(measured_curve_problem(curve(0.15, 0.88), A0).find("sum of the junction areas") != std::string::npos);
  // A linear A(Q) with a 30 % decay (the published maximum): its quadratic intercept is off by
  // 0.1875 · 30 % = 5.6 % (closed form of the least-squares fit of t by t² on [0, 1]): accepted.
  MeasuredCurve lin;
  for (int i = 0; i < 200; ++i) {
    const double t = i / 199.0;
    lin.Q_N.push_back(Qs * t);
    lin.A_m2.push_back(A0 * (1 - 0.3 * t));
  }
  CHECK(measured_curve_problem(lin, A0).empty());
  const MeasuredCurve two{{0.0, 1.0}, {A0, 0.9 * A0}};
  CHECK(measured_curve_problem(two, A0).find("at least 3") != std::string::npos);
}
