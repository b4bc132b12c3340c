// Multi-start fits and their convergence verdict (fit/convergence.hpp): the Sobol design of
// starts, the basin rule, a two-well landscape that defeats one local start and that several
// starts certify, and a mutant optimizer that stops at its first point and must not pass.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <set>

#include "fit/convergence.hpp"
#include "fit/fit.hpp"
#include "fit/fit_journal.hpp"
#include "fit/fit_load.hpp"
#include "fit_support.hpp"

using namespace asperity;
using namespace asperity::testing;
namespace fs = std::filesystem;

namespace {

// Two wells in the scaled coordinates u of (eta: log on [30, 300], epsilon: linear on
// [0.5, 0.99]): J = 1 + 10 |u − a|² (c + |u − b|²) is exactly 1 at a (the global minimum) and
// has a local minimum near b, J ≈ 1.30, whose basin holds the file's start. (The factor 10 keeps
// distinct points apart by more than the basin tolerance: without it the centre, J = 1.0351, and
// the Sobol point (0.375, 0.375), J = 1.0357, would share a "basin".)
constexpr double kA[2] = {0.8, 0.75}, kB[2] = {0.2, 0.2}, kC = 0.05;

double two_wells(double eta, double epsilon) {
  const double u[2] = {std::log(eta / 30.0) / std::log(10.0), (epsilon - 0.5) / 0.49};
  const double da = (u[0] - kA[0]) * (u[0] - kA[0]) + (u[1] - kA[1]) * (u[1] - kA[1]);
  const double db = (u[0] - kB[0]) * (u[0] - kB[0]) + (u[1] - kB[1]) * (u[1] - kB[1]);
  return 1.0 + 10.0 * da * (kC + db);
}

// The truth: a in SI.
const double kEtaTruth = 30.0 * std::pow(10.0, kA[0]), kEpsilonTruth = 0.5 + 0.49 * kA[1];

// A small population (26 junctions, a run to the first peak in milliseconds) scored by the
// closed-form landscape of its scene's (eta, epsilon): the model runs as in any fit, the
// objective is known exactly.
struct WellsCase {
  FitCase base = make_fit_case("wells", 0.7e-15, 1.5, 0.1, 20);
  ~WellsCase() {
    std::error_code ec;
    fs::remove_all(base.dir, ec);
  }
};

const WellsCase& wells_case() {
  static const WellsCase c;
  return c;
}

FitResult fit_wells(const std::string& optimizer, FitJournal* journal = nullptr) {
  const auto f = write_text(wells_case().base.dir / "wells.yaml",
                            "experiments: [{scene: scene.yaml, set: {stop.at_first_peak: true}}]\n"
                            "parameters:\n"
                            "  model.eta: {lo: 30, hi: 300, start: 40, scale: log}\n"
                            "  model.epsilon: {lo: 0.5, hi: 0.99, start: 0.55}\n"
                            "optimizer: " +
                                optimizer +
                                "\n"
                                "profile: false\n");
  FitLoadOptions lo;
  lo.user_objective = true;
  const FitSpec spec = load_fit(f, {}, lo);
  FitOptions o;
  o.threads = 2;
  o.profile = o.error_bars = false;
  o.journal = journal;
  o.user_term = [](const FitExperiment&, const Scene& scene, const RunResult&) {
    return two_wells(scene.model.eta, scene.model.epsilon);
  };
  return run_fit(spec, o);
}

}  // namespace

TEST_CASE("sobol_starts: deterministic points inside the box, without the centre or the file's start",
          "[fit][convergence]") {
  const auto a = sobol_starts(3, 7), b = sobol_starts(3, 7);
  REQUIRE(a.size() == 7);
  CHECK(a == b);
  std::set<std::vector<double>> distinct(a.begin(), a.end());
  CHECK(distinct.size() == 7);
  for (const auto& u : a) {
    REQUIRE(u.size() == 3);
    CHECK(u != std::vector<double>{0.5, 0.5, 0.5});  // DIRECT's first point
    for (const double x : u) CHECK((x > 0 && x < 1));
  }
  // Boost's sequence after its centre starts at (0.75, 0.25, 0.25); a start there is skipped.
  CHECK(a[0] == std::vector<double>{0.75, 0.25, 0.25});
  const auto c = sobol_starts(3, 7, {0.75, 0.25, 0.25});
  CHECK(c[0] == a[1]);
  CHECK(c.size() == 7);
}

TEST_CASE(
    "judge_convergence: two starts in the best basin certify it, one start is unverified, a lone best is not converged",
    "[fit][convergence]") {
  const BasinRule rule{1e-3, 1e-3};
  SECTION("by objective") {
    const ConvergenceVerdict v = judge_convergence({{{0.1, 0.1}, 2.0}, {{0.8, 0.8}, 1.0}, {{0.81, 0.8}, 1.0009}}, rule);
    CHECK(v.converged == Converged::yes);
    CHECK(v.best == 1);
    CHECK(v.in_basin == 2);
    CHECK(v.in_best_basin == std::vector<bool>{false, true, true});
    CHECK(v.spread == Approx(0.01));
  }
  SECTION("by distance, where the objective is near zero") {
    const ConvergenceVerdict v =
        judge_convergence({{{0.5, 0.5}, 1e-12}, {{0.5, 0.5004}, 3e-12}, {{0.1, 0.1}, 0.3}}, rule);
    CHECK(v.converged == Converged::yes);
    CHECK(v.in_basin == 2);
  }
  SECTION("only the best start") {
    const ConvergenceVerdict v = judge_convergence({{{0.1, 0.1}, 1.1}, {{0.8, 0.8}, 1.0}, {{0.5, 0.5}, 1.002}}, rule);
    CHECK(v.converged == Converged::no);
    CHECK(v.in_basin == 1);
    CHECK(v.reason.find("only 1 of 3 starts") == 0);
  }
  SECTION("a single start") {
    const ConvergenceVerdict v = judge_convergence({{{0.8, 0.8}, 1.0}}, rule);
    CHECK(v.converged == Converged::unverified);
    CHECK(v.in_basin == 1);
  }
  SECTION("a failed start is in no basin") {
    const ConvergenceVerdict v = judge_convergence({{{0.8, 0.8}, 1.0}, {{0.8, 0.8}, std::nan("")}}, rule);
    CHECK(v.converged == Converged::no);
  }
}

TEST_CASE(
    "A two-well landscape: one local start stops in the wrong well, eight starts find the global minimum and certify "
    "it",
    "[fit][convergence]") {
  const FitResult one = fit_wells("{algorithm: LN_BOBYQA, xtol_rel: 1e-6, max_evaluations: 200}");
  REQUIRE(one.fits.size() == 1);
  const Optimization& a = one.fits[0];
  INFO(a.failure);
  REQUIRE(a.ok());
  CHECK(a.objective > 1.2);  // the local well (J ≈ 1.30)
  CHECK(a.converged == Converged::unverified);
  CHECK(a.starts.size() == 1);

  const FitResult many = fit_wells("{algorithm: LN_BOBYQA, xtol_rel: 1e-6, max_evaluations: 200, starts: 8}");
  const Optimization& b = many.fits[0];
  INFO(b.failure << "; " << b.convergence);
  REQUIRE(b.ok());
  CHECK(b.starts.size() == 8);
  CHECK(b.objective <= 1.0 * (1 + 1e-3));  // J_truth = 1
  CHECK(std::abs(b.best[0] / kEtaTruth - 1) < 1e-3);
  CHECK(std::abs(b.best[1] / kEpsilonTruth - 1) < 1e-3);
  CHECK(b.converged == Converged::yes);
  CHECK(b.in_best_basin >= 2);
  CHECK(b.spread < 1e-3);
  CHECK(!b.starts[0].in_best_basin);  // the file's start is still in the local well
  // Every start's evaluations are in the log, numbered on.
  int total = 0;
  for (const StartRun& s : b.starts) total += s.evaluations;
  CHECK(total == b.evaluations);
  CHECK(static_cast<int>(b.log.size()) == b.evaluations);
  CHECK(b.log.back().index == b.evaluations);
}

TEST_CASE("A mutant optimizer that returns its first lattice point is reported not converged", "[fit][convergence]") {
  // DIRECT stopped at its first point (the centre) and every start's local stage at its start:
  // four optima that are just the four first points.
  const FitResult r = fit_wells(
      "{algorithm: GN_DIRECT_L, max_evaluations: 1, starts: 4, "
      "polish: {algorithm: LN_BOBYQA, max_evaluations: 1}}");
  const Optimization& o = r.fits[0];
  INFO(o.failure << "; " << o.convergence);
  REQUIRE(o.ok());
  CHECK(o.starts.size() == 4);
  REQUIRE(o.starts[0].best.size() == 2);  // the centre of the scaled box
  CHECK(o.starts[0].best[0] == Approx(std::sqrt(30.0 * 300.0)).epsilon(1e-12));
  CHECK(o.starts[0].best[1] == Approx(0.745).epsilon(1e-12));
  CHECK(o.converged == Converged::no);
  CHECK(o.in_best_basin == 1);
  CHECK(o.convergence.find("only 1 of 4 starts") == 0);
}

TEST_CASE("A multi-start fit replays from its journal: the same starts, evaluations and verdict",
          "[fit][convergence][journal]") {
  const fs::path d = fresh_dir("asperity-fitconv-journal");
  const std::string optimizer = "{algorithm: LN_BOBYQA, xtol_rel: 1e-6, max_evaluations: 200, starts: 4}";
  FitResult first, again;
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    first = fit_wells(optimizer, &j);
  }
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    again = fit_wells(optimizer, &j);
  }
  const Optimization &f = first.fits[0], &g = again.fits[0];
  CHECK(again.computed == 0);
  CHECK(again.replayed == f.evaluations);
  CHECK(g.evaluations == f.evaluations);
  CHECK(g.objective == f.objective);
  CHECK(g.best == f.best);
  CHECK(g.converged == f.converged);
  CHECK(g.best_start == f.best_start);
  for (std::size_t k = 0; k < f.starts.size(); ++k) CHECK(g.starts[k].evaluations == f.starts[k].evaluations);
  fs::remove_all(d);
}
