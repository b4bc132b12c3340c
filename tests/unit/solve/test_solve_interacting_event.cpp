// The fast (event) solver for interacting junctions (docs/model.md §8) against independent truths:
// the independent event solver when the junctions are far apart, the 2x2 closed form of a pair,
// the step-by-step interacting reference (first order in dt, its dt → 0 limit), no force jump
// at a repin, and the closed-form avalanche of a chain.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <vector>

#include "observe/recorder.hpp"
#include "observe/simulate.hpp"
#include "physics/elastic_interaction.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"
#include "solve/interacting/interacting_junctions.hpp"
#include "solve/interacting/interacting_reference_stepper.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "support_scenes.hpp"

using namespace asperity;
using namespace asperity::testing;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

Scene interacting_event_scene(std::vector<double> areas, std::vector<double> x, std::vector<double> y) {
  return interacting_scene(std::move(areas), std::move(x), std::move(y), SolverMethod::event);
}

// A compact cluster: n junctions on a square lattice of pitch `pitch_m`.
void cluster(std::size_t n, double pitch_m, std::vector<double>& x, std::vector<double>& y) {
  const std::size_t side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (std::size_t i = 0; i < n; ++i) {
    x.push_back(pitch_m * static_cast<double>(i % side));
    y.push_back(pitch_m * static_cast<double>(i / side));
  }
}

// n junctions of 1e-9 to 4e-9 m² on a square lattice 1.6 largest diameters apart (strong coupling).
Scene strong_cluster_scene(std::size_t n) {
  const std::vector<double> areas = spread_areas(n, 1e-9, 4e-9);
  std::vector<double> x, y;
  cluster(areas.size(), 1.6 * 2 * std::sqrt(4e-9 / M_PI), x, y);
  return interacting_event_scene(areas, x, y);
}

}  // namespace

TEST_CASE("event solver: junctions far apart reproduce the independent event solver on every observable",
          "[solve][interacting][event][heavy]") {
  // The stand-in P0.98N (294 junctions; stick-slip: slips and a repin inside the window) with
  // its junctions 10^7 m apart, where the coupling is ~1e-12 of a junction's own compliance.
  Scene inter = load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P0.98N.yaml");
  const std::size_t n = inter.experiment.junctions.size();
  inter.experiment.junctions.x_m.clear();
  inter.experiment.junctions.y_m.clear();
  for (std::size_t i = 0; i < n; ++i) {
    inter.experiment.junctions.x_m.push_back(1e7 * static_cast<double>(i % 20));
    inter.experiment.junctions.y_m.push_back(1e7 * static_cast<double>(i / 20));
  }
  inter.model.interactions = Interactions::elastic;
  inter.stop.time = 1.5;
  Scene indep = inter;
  indep.model.interactions = Interactions::none;
  const RunResult b = simulate(indep);
  REQUIRE(std::isfinite(b.obs.Q_s));
  REQUIRE(b.info.stats.repins >= 1);  // the window holds slips and a repin
  // Converged solves (interaction tolerance 1e-12): the limit to 1e-9. At the default (1e-8) the
  // peak within 3e-9 and the series within 3e-8 (measured 2026-11-25: Q_s 5.0e-10, A_s 6.3e-11,
  // t_peak 4.6e-11; the series 9.5e-9, the stick-slip after the peak carrying the solves' error).
  const double tols[2] = {1e-12, inter.solver.interaction_tolerance};
  const double peak_bound[2] = {1e-9, 3e-9}, series_bound[2] = {1e-9, 3e-8};
  for (int k = 0; k < 2; ++k) {
    INFO("interaction tolerance " << tols[k]);
    inter.solver.interaction_tolerance = tols[k];
    const RunResult a = simulate(inter);
    CHECK(a.info.stats.slips == b.info.stats.slips);
    CHECK(a.info.stats.repins == b.info.stats.repins);
    CHECK_THAT(a.obs.Q_s, WithinRel(b.obs.Q_s, peak_bound[k]));
    CHECK_THAT(a.obs.A_s, WithinRel(b.obs.A_s, peak_bound[k]));
    CHECK_THAT(a.obs.t_peak, WithinRel(b.obs.t_peak, peak_bound[k]));
    REQUIRE(a.recorder.series().size() == b.recorder.series().size());
    double worst = 0;
    for (std::size_t m = 0; m < a.recorder.series().size(); ++m) {
      const Sample &u = a.recorder.series()[m], &v = b.recorder.series()[m];
      worst = std::max({worst, std::abs(u.Q - v.Q) / (std::abs(v.Q) + 1e-3), std::abs(u.A - v.A) / v.A,
                        std::abs(u.X - v.X) / (std::abs(v.X) + 1e-9)});
      CHECK(u.n_slipping == v.n_slipping);
    }
    CHECK(worst < series_bound[k]);
  }
}

TEST_CASE("event solver: a pair of linear junctions has the 2x2 closed-form stiffness and force sharing",
          "[solve][interacting][event]") {
  Scene s = interacting_event_scene({1e-9, 2.5e-9}, {0, 8e-5}, {0, 3e-5});
  s.model.alpha_b = 0;  // constant areas: linear until the first slip
  const Problem p = make_problem(s);
  InteractingJunctions J(p);
  const double k1 = p.law.stiffness(1e-9, 1e-9), k2 = p.law.stiffness(2.5e-9, 2.5e-9);
  const double a = 1 / k1, d = 1 / k2;
  const double c = disc_compliance(-8e-5, -3e-5, std::sqrt(1e-9 / M_PI), std::sqrt(2.5e-9 / M_PI), p.law.E, p.law.nu);
  const double det = a * d - c * c;
  const double X = 2e-6;
  CHECK_THAT(J.force(X), WithinRel(X * (a + d - 2 * c) / det, 1e-12));
  const std::vector<double> f = J.forces(X);
  CHECK_THAT(f[0], WithinRel(X * (d - c) / det, 1e-12));
  CHECK_THAT(f[1], WithinRel(X * (a - c) / det, 1e-12));
  // The first slip is the junction that reaches σA first: X = σA_i det/(coefficient).
  const double sigma = p.law.sigma;
  const double X1 = sigma * 1e-9 * det / (d - c), X2 = sigma * 2.5e-9 * det / (a - c);
  CHECK_THAT(J.next_threshold(), WithinRel(std::min(X1, X2), 1e-12));
}

TEST_CASE("event solver: the step-by-step interacting reference converges to it at first order in dt",
          "[solve][interacting][event]") {
  // 16 junctions 1.6 diameters apart (strong coupling), to the first peak. The measure is the
  // mean |Q_ref − Q_event| over the samples of the loading branch, relative to Q_s: the peak's
  // own time and height jitter with the sampling grid, the whole curve does not.
  Scene ev = strong_cluster_scene(16);
  ev.stop.at_first_peak = true;
  ev.solver.tolerance = 1e-11;
  const RunResult e = simulate(ev);
  REQUIRE(std::isfinite(e.obs.Q_s));
  REQUIRE(e.info.stats.slips == 16);
  const double Ct[4] = {200, 400, 800, 1600};
  double err[4];
  for (int k = 0; k < 4; ++k) {
    Scene r = ev;
    r.solver.method = SolverMethod::reference;
    r.solver.Ct = Ct[k];
    const RunResult ref = simulate(r);
    const auto &A = ref.recorder.series(), &B = e.recorder.series();
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t j = 0; j < std::min(A.size(), B.size()) && B[j].t <= e.obs.t_peak; ++j, ++n)
      sum += std::abs(A[j].Q - B[j].Q);
    REQUIRE(n > 100);
    err[k] = sum / static_cast<double>(n) / e.obs.Q_s;
  }
  // Measured (2026-11-24): 7.5e-3, 3.8e-3, 1.85e-3, 9.3e-4: the error halves with dt.
  INFO("errors " << err[0] << " " << err[1] << " " << err[2] << " " << err[3]);
  for (int k = 0; k < 3; ++k) {
    CHECK(err[k] / err[k + 1] > 1.8);
    CHECK(err[k] / err[k + 1] < 2.2);
  }
  CHECK(err[3] < 2e-3);
}

TEST_CASE("event solver: a repin carries every force over without a jump", "[solve][interacting][event]") {
  const std::vector<double> areas = spread_areas(9, 1e-9, 3e-9);
  std::vector<double> x, y;
  cluster(areas.size(), 2.2 * std::sqrt(3e-9 / M_PI) * 2, x, y);
  Scene s = interacting_event_scene(areas, x, y);
  // Converged solves: the property is the repin's (its anchors), not the solves' tolerance.
  s.solver.interaction_tolerance = 1e-12;
  const Problem p = make_problem(s);
  InteractingJunctions J(p);
  // Load to the first slip, let it happen, then repin everything at the same X.
  const double X = J.next_threshold();
  REQUIRE(J.slip_crossed(X) >= 1);
  const std::vector<double> before = J.forces(X);
  const double F = J.force(X);
  J.repin_all(X);
  CHECK(J.n_slipping() == 0);
  const std::vector<double> after = J.forces(X);
  for (std::size_t i = 0; i < before.size(); ++i) CHECK_THAT(after[i], WithinRel(before[i], 1e-12));
  CHECK_THAT(J.force(X), WithinRel(F, 1e-12));
}

TEST_CASE("event solver: a chain of three equal junctions slips in the closed-form order and avalanches",
          "[solve][interacting][event]") {
  // Three equal linear junctions in a row across the shear (along y), spacing d, the cut-off
  // keeping nearest neighbours only: compliance a = 1/k on the diagonal, c between neighbours.
  // Loaded from rest, f = X M⁻¹1: the ends carry (a − c)/(a² − 2c²) X, more than the middle, and
  // slip first at X_e = f_s (a² − 2c²)/(a − c) (one of them: by symmetry either). With that end at
  // ε f_s the other end reaches f_s at X_B = f_s ((a² − c²) − εc²)/(a − c); once both ends slip
  // the middle carries f_m = (X − 2cεf_s)/a, so it goes with the second end (an avalanche at
  // fixed X) iff f_m(X_B) ≥ f_s, else alone at X_m = f_s (a + 2cε).
  const double A = 2e-9, d = 2.5 * 2 * std::sqrt(A / M_PI);
  for (const double eps : {0.9, 0.3}) {
    Scene s = interacting_event_scene({A, A, A}, {0, 0, 0}, {0, d, 2 * d});
    s.model.alpha_b = 0;
    s.model.epsilon = eps;
    s.model.interaction_cutoff = 1.5 * d;
    const Problem p = make_problem(s);
    InteractingJunctions J(p);
    const double a = 1 / J.state().k[0], c = interaction_matrix(p)(0, 1), f_s = J.state().f_s[0];
    REQUIRE(interaction_matrix(p)(0, 2) == 0.0);
    const double X_e = f_s * (a * a - 2 * c * c) / (a - c);
    const double X_B = f_s * ((a * a - c * c) - eps * c * c) / (a - c);
    const double f_m = (X_B - 2 * c * eps * f_s) / a;
    INFO("epsilon " << eps << ", c/a " << c / a << ", f_m(X_B)/f_s " << f_m / f_s);
    REQUIRE((f_m >= f_s) == (eps < 0.5));  // measured 0.922 at ε = 0.9, 1.032 at ε = 0.3 (c/a = 0.0875)
    CHECK_THAT(J.next_threshold(), WithinRel(X_e, 1e-12));
    CHECK(J.slip_crossed(J.next_threshold()) == 1);  // one end; the other end is unloaded by it
    CHECK_THAT(J.next_threshold(), WithinRel(X_B, 1e-12));
    const std::int64_t second = J.slip_crossed(J.next_threshold());
    if (f_m >= f_s) {
      CHECK(second == 2);  // the middle goes with the second end: an avalanche
      CHECK(J.n_slipping() == 3);
    } else {
      CHECK(second == 1);
      CHECK_THAT(J.next_threshold(), WithinRel(f_s * (a + 2 * c * eps), 1e-12));  // the middle alone
      CHECK(J.slip_crossed(J.next_threshold()) == 1);
    }
  }
}

TEST_CASE("event solver: an avalanche past the run's deadline stops after its first slip, counted",
          "[solve][interacting][event]") {
  // The chain above at ε = 0.3, where the second end's slip takes the middle with it (an avalanche
  // of two at fixed X). With the deadline passed, the event's first slip happens and the avalanche
  // stops before the next: WallTimeReached, two junctions slipping instead of three, and the state
  // still solvable (the forces of the set as it stands).
  const double A = 2e-9, d = 2.5 * 2 * std::sqrt(A / M_PI);
  Scene s = interacting_event_scene({A, A, A}, {0, 0, 0}, {0, d, 2 * d});
  s.model.alpha_b = 0;
  s.model.epsilon = 0.3;
  s.model.interaction_cutoff = 1.5 * d;
  const Problem p = make_problem(s);
  for (const bool passed : {false, true}) {
    InteractingJunctions J(p);
    REQUIRE(J.slip_crossed(J.next_threshold()) == 1);
    if (passed) J.set_deadline(std::chrono::steady_clock::now());
    const double X = J.next_threshold();
    if (passed) {
      CHECK_THROWS_AS(J.slip_crossed(X), WallTimeReached);
      CHECK(J.n_slipping() == 2);
      CHECK(J.slips() == 2);
      const std::vector<double> f = J.forces(X);  // the middle, still pinned, over its slip force
      CHECK(f[1] >= J.state().f_s[1]);
    } else {
      CHECK(J.slip_crossed(X) == 2);
      CHECK(J.n_slipping() == 3);
      CHECK(J.slips() == 3);
    }
  }
}

TEST_CASE("event solver: a chord pass past the run's deadline stops the solve, and the run as a wall-time limit",
          "[solve][interacting][event]") {
  // 25 Eq. (3) junctions, strongly coupled: every solve iterates. With the deadline passed, the
  // next solve stops at its first pass; with none, the same forces as a population never given one.
  const Problem p = make_problem(strong_cluster_scene(25));
  InteractingJunctions J(p), fresh(p);
  const double X = 0.5 * J.next_threshold();
  J.set_deadline(std::chrono::steady_clock::now());
  CHECK_THROWS_AS(J.forces(X), WallTimeReached);
  J.clear_deadline();
  const std::vector<double> f = J.forces(X), g = fresh.forces(X);
  for (std::size_t i = 0; i < f.size(); ++i) CHECK_THAT(f[i], WithinRel(g[i], 1e-12));
  // A run whose limit (1 ns) has passed by its first solve, in the stepper's set-up (the first
  // event search): stopped there, as a wall-time limit, at t = 0.
  Problem q = make_problem(strong_cluster_scene(25));
  q.limits.wall_time_s = 1e-9;
  Recorder rec = make_recorder(strong_cluster_scene(25));
  const RunInfo info = integrate(q, rec);
  CHECK(info.stopped_by == LimitHit::wall_time);
  CHECK(info.t_end == 0.0);
  CHECK(info.stats.slips == 0);
}

TEST_CASE("interacting reference: a step past the run's deadline stops inside it, before its next dense solve",
          "[solve][interacting][reference]") {
  // The step-by-step interacting reference solves the coupled system densely, O(N³), once per
  // Newton iteration and per avalanche round: a step can hold many. (1) 25 Eq. (3) junctions,
  // strongly coupled: every coupled solve iterates. With the deadline passed the step throws at
  // its second iteration, every force as it was; cleared, the step gives a fresh stepper's forces.
  {
    Scene sc = strong_cluster_scene(25);
    sc.solver.method = SolverMethod::reference;
    const Problem p = make_problem(sc);
    Recorder rec1 = make_recorder(sc), rec2 = make_recorder(sc);
    ObserverAdapter<Recorder> r1(rec1), r2(rec2);
    InteractingReferenceStepper st(p), fresh(p);
    st.start(r1);
    fresh.start(r2);
    for (int k = 0; k < 3; ++k) st.advance(r1), fresh.advance(r2);
    const std::vector<double> before = st.junctions().force;
    st.set_deadline(std::chrono::steady_clock::now());
    CHECK_THROWS_AS(st.advance(r1), WallTimeReached);
    CHECK(st.junctions().force == before);
    st.clear_deadline();
    st.advance(r1);
    fresh.advance(r2);
    for (std::size_t i = 0; i < before.size(); ++i) CHECK(st.junctions().force[i] == fresh.junctions().force[i]);
  }
  // (2) The closed-form chain at ε = 0.3 (linear junctions: one solve per round). Equal ends carry
  // equal forces: in the step where they reach their slip force both slip in its first round, and
  // the middle, loaded by them, in a second round (f_m ≥ f_s, see the event solver's chain test).
  // With the deadline passed before that step, the second round is not solved: the middle stays
  // pinned.
  const double A = 2e-9, d = 2.5 * 2 * std::sqrt(A / M_PI);
  Scene s = interacting_event_scene({A, A, A}, {0, 0, 0}, {0, d, 2 * d});
  s.solver.method = SolverMethod::reference;
  s.model.alpha_b = 0;
  s.model.epsilon = 0.3;
  s.model.interaction_cutoff = 1.5 * d;
  const Problem p = make_problem(s);
  auto pinned = [](const InteractingReferenceStepper& st) {
    int n = 0;
    for (auto b : st.junctions().pinned) n += b ? 1 : 0;
    return n;
  };
  Recorder rec1 = make_recorder(s), rec2 = make_recorder(s);
  ObserverAdapter<Recorder> r1(rec1), r2(rec2);
  InteractingReferenceStepper ahead(p), st(p);  // ahead: one step further
  ahead.start(r1);
  st.start(r2);
  ahead.advance(r1);
  while (pinned(ahead) == 3 && !ahead.finished()) ahead.advance(r1), st.advance(r2);
  REQUIRE(pinned(ahead) == 0);  // all three in one step
  REQUIRE(pinned(st) == 3);     // st: the step before
  st.set_deadline(std::chrono::steady_clock::now());
  CHECK_THROWS_AS(st.advance(r2), WallTimeReached);
  CHECK(pinned(st) == 1);
  CHECK(st.junctions().pinned[1] != 0);  // the middle
}

TEST_CASE("event solver: each coupled solve is within solver.interaction_tolerance of the converged one",
          "[solve][interacting][event]") {
  // 25 Eq. (3) junctions 1.6 diameters apart (strong coupling): the forces at half the first slip
  // position and, after that slip, at the new set's next one, against solves converged to 1e-12,
  // relative to each junction's slip force: below the knob (its contract), and falling faster
  // than it.
  Scene s = strong_cluster_scene(25);
  // Both at the converged run's positions (the same X for all): half its first slip position,
  // and its second.
  double X1 = 0, X2 = 0;
  auto forces_at = [&](double tol) {
    s.solver.interaction_tolerance = tol;
    const Problem p = make_problem(s);
    InteractingJunctions J(p);
    if (X1 == 0) X1 = J.next_threshold();
    std::vector<double> f = J.forces(0.5 * X1);
    REQUIRE(J.slip_crossed(J.next_threshold()) >= 1);
    if (X2 == 0) X2 = J.next_threshold();
    const std::vector<double> g = J.forces(X2);
    f.insert(f.end(), g.begin(), g.end());
    return std::make_pair(f, J.state().f_s);
  };
  const auto [ref, fs] = forces_at(1e-12);
  const double tols[3] = {1e-4, 1e-6, 1e-8};
  double err[3];
  for (int k = 0; k < 3; ++k) {
    const auto [f, unused] = forces_at(tols[k]);
    err[k] = 0;
    for (std::size_t i = 0; i < f.size(); ++i) err[k] = std::max(err[k], std::abs(f[i] - ref[i]) / fs[i % fs.size()]);
  }
  // Measured (2026-11-25): 6.2e-6, 7.7e-9, 1.9e-12, i.e. 0.06, 0.008 and 0.0002 of the knob; the
  // order in the knob log10(ratio)/2 = 1.45 and 1.80 (faster than the knob: the chord iteration
  // contracts by 0.02-0.1 a pass and stops at its first change below the tolerance).
  INFO("errors " << err[0] << " " << err[1] << " " << err[2]);
  CHECK(err[0] < 0.2 * tols[0]);
  CHECK(err[1] < 0.03 * tols[1]);
  CHECK(err[2] < 1e-3 * tols[2]);
  CHECK(err[0] / err[1] > 250);  // order > 1.2
  CHECK(err[1] / err[2] > 250);
}

TEST_CASE("event solver: chord passes on G's single-precision copy keep every slip position within the tolerance",
          "[solve][interacting][event]") {
  // 100 Eq. (3) junctions 1.6 diameters apart (strong coupling), their first 40 slips (five folds
  // of removals into G), with G's single-precision copy kept (as from N = 2,048 on) and without,
  // at the default tolerance, against the converged solves (1e-12, double): slip positions
  // relative to X, forces at the last one relative to each slip force.
  Scene s = strong_cluster_scene(100);
  auto run = [&](double tol, std::size_t single_from, std::int64_t* single_passes) {
    s.solver.interaction_tolerance = tol;
    const Problem p = make_problem(s);
    InteractingJunctions J(p, single_from);
    std::vector<double> out;
    while (J.slips() < 40) {
      REQUIRE(J.has_threshold());
      out.push_back(J.next_threshold());
      J.slip_crossed(J.next_threshold());
    }
    const std::vector<double> f = J.forces(out.back());
    for (std::size_t i = 0; i < f.size(); ++i) out.push_back(f[i] / J.state().f_s[i]);
    if (single_passes) *single_passes = J.work().single_passes;
    return out;
  };
  const std::size_t never = static_cast<std::size_t>(-1);
  std::int64_t single = 0;
  const std::vector<double> ref = run(1e-12, never, nullptr), dbl = run(1e-8, never, nullptr),
                            sgl = run(1e-8, 0, &single);
  REQUIRE(sgl.size() == ref.size());
  REQUIRE(dbl.size() == ref.size());
  // Slip positions relative to themselves, then forces relative to the slip forces.
  double x_single = 0, x_double = 0, f_single = 0, f_double = 0, x_apart = 0, f_apart = 0;
  for (std::size_t k = 0; k < ref.size(); ++k) {
    (k < 40 ? x_apart : f_apart) =
        std::max(k < 40 ? x_apart : f_apart, std::abs(sgl[k] - dbl[k]) / (k < 40 ? std::abs(ref[k]) : 1.0));
    const double scale = k < 40 ? std::abs(ref[k]) : 1.0;
    double& es = k < 40 ? x_single : f_single;
    double& ed = k < 40 ? x_double : f_double;
    es = std::max(es, std::abs(sgl[k] - ref[k]) / scale);
    ed = std::max(ed, std::abs(dbl[k] - ref[k]) / scale);
  }
  INFO("single passes " << single << "; with the copy: X " << x_single << ", f " << f_single << "; double only: X "
                        << x_double << ", f " << f_double << "; apart: X " << x_apart << ", f " << f_apart);
  // Measured: 467 single passes; forces 6.3e-9 of the slip forces off the converged ones with the
  // copy and without (the tolerance's own error); the two runs 5.9e-11 apart in force and 7.9e-11
  // in slip position (each pass may err by 0.1 of the tolerance, and errs by far less).
  CHECK(single > 0);
  CHECK(f_single < 1e-8);
  CHECK(f_apart < 3e-10);
  CHECK(x_apart < 4e-10);
}

TEST_CASE("event solver: at the default interaction tolerance a stand-in's peak and stick-slip are within 5e-9",
          "[solve][interacting][event][heavy]") {
  // The stand-in P0.98N with its junctions 4 times farther apart (weakly coupled, avalanches at
  // the peak, five stick-slip cycles; the interaction sweep's most sensitive point), at the
  // default solver.interaction_tolerance and at 1e-12. Issue 26 asks 1e-7. Measured (2026-11-25),
  // relative: Q_s 2.7e-11, A_s 8.1e-12, t_peak 8.6e-11, stick-slip period 3.8e-10, drop 1.3e-9; at
  // 1e-7 Q_s would move by 7.6e-8 and the drop by 3.4e-7.
  Scene s = load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P0.98N.yaml",
                       {"model.interactions=elastic", "model.position_scale=4", "stop.time=20", "stop.cycles=5"});
  s.output.series.clear();
  REQUIRE(s.solver.interaction_tolerance == 1e-8);
  Scene converged = s;
  converged.solver.interaction_tolerance = 1e-12;
  const RunResult a = simulate(s), b = simulate(converged);
  REQUIRE(std::isfinite(b.obs.Q_s));
  REQUIRE(b.obs.ss_cycles == 5);
  CHECK(a.obs.ss_cycles == b.obs.ss_cycles);
  CHECK(a.info.stats.slips == b.info.stats.slips);
  CHECK_THAT(a.obs.Q_s, WithinRel(b.obs.Q_s, 5e-9));
  CHECK_THAT(a.obs.A_s, WithinRel(b.obs.A_s, 5e-9));
  CHECK_THAT(a.obs.t_peak, WithinRel(b.obs.t_peak, 5e-9));
  CHECK_THAT(a.obs.ss_period, WithinRel(b.obs.ss_period, 5e-9));
  CHECK_THAT(a.obs.ss_drop, WithinRel(b.obs.ss_drop, 5e-9));
}

TEST_CASE("event solver: a junction driven far past its slip force in an avalanche slips in it",
          "[solve][interacting][event]") {
  // Two never-slipped junctions whose areas follow Eq. (3), a small one (a) beside a larger one
  // (b), their centres 1.1 times the sum of their radii apart: a slips first, at X* where f_a = f_s,a and
  //   u_a(f_s,a) + c f_b = X*,  u_b(f_b) + c f_s,a = X*,   u(f) = f / k(A(f)),
  // a 1-D root in f_b. Slipping, a carries ε f_s,a, so b's own displacement jumps to
  // D = X* − c ε f_s,a. b slips in the same avalanche iff D ≥ δ_s,b = u_b(f_s,b). The area of b
  // is set (bisection) so that D = (1 + m) δ_s,b for a known margin m: far past (m = +0.05,
  // about 1e10 times the rounding of any kernel's sums) it must slip with a; short of it
  // (m = −0.05) it must not. Both sides follow from the closed form, not from the last bits of C.
  const double Aa = 1e-9, eps = 0.5;
  const auto pair_scene = [&](double Ab) {
    const double d = 1.1 * (std::sqrt(Aa / M_PI) + std::sqrt(Ab / M_PI));
    Scene s = interacting_event_scene({Aa, Ab}, {0, d}, {0, 0});
    s.model.epsilon = eps;
    return s;
  };
  struct ClosedForm {
    double X, D, delta_sb, before;  // before: b's own displacement before a's slip, of δ_s,b
  };
  const auto closed_form = [&](double Ab) {
    const Scene s = pair_scene(Ab);
    const Problem p = make_problem(s);
    const ContactLaw& law = p.law;
    const double c = interaction_matrix(p)(0, 1);
    const auto u = [&](double A0, double f) { return f / law.stiffness(A0, law.area(A0, f)); };
    const double fsa = law.slip_phi(Aa) / law.force_scale(Aa), fsb = law.slip_phi(Ab) / law.force_scale(Ab);
    // g(f_b) = u_b(f_b) − c f_b − (u_a(f_s,a) − c f_s,a): increasing (u_b' ≥ 1/k_b(A0) > c).
    double lo = 0, hi = fsb;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (u(Ab, mid) - c * mid < u(Aa, fsa) - c * fsa ? lo : hi) = mid;
    }
    const double X = u(Aa, fsa) + c * lo;
    return ClosedForm{X, X - c * eps * fsa, u(Ab, fsb), (X - c * fsa) / u(Ab, fsb)};
  };
  for (const double margin : {0.05, -0.05}) {
    // D/δ_s,b falls as b grows (its slip displacement grows as √A0): bisect in log A_b.
    double lo = std::log(1e-9), hi = std::log(4e-9);
    REQUIRE(closed_form(std::exp(lo)).D / closed_form(std::exp(lo)).delta_sb > 1 + margin);
    REQUIRE(closed_form(std::exp(hi)).D / closed_form(std::exp(hi)).delta_sb < 1 + margin);
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      const ClosedForm cf = closed_form(std::exp(mid));
      (cf.D / cf.delta_sb > 1 + margin ? lo : hi) = mid;
    }
    const double Ab = std::exp(lo);
    const ClosedForm cf = closed_form(Ab);
    const Scene s = pair_scene(Ab);
    const Problem p = make_problem(s);
    InteractingJunctions J(p);
    INFO("margin " << margin << ": A_b " << Ab << " m^2, b's displacement before a's slip " << cf.before
                   << " of its slip displacement, after " << cf.D / cf.delta_sb);
    REQUIRE(cf.before < 0.97);  // b is well short of its threshold until a slips
    CHECK_THAT(J.next_threshold(), WithinRel(cf.X, 1e-9));
    const std::int64_t slipped = J.slip_crossed(J.next_threshold());
    INFO("junctions slipped as driven past phi = 1: " << J.work().overloaded);
    if (margin > 0) {
      CHECK(slipped == 2);  // b goes with a, at the same X
      CHECK(J.n_slipping() == 2);
    } else {
      CHECK(slipped == 1);
      CHECK(J.n_slipping() == 1);
      CHECK(J.next_threshold() > cf.X);  // b slips later, alone
    }
  }
}

TEST_CASE("event solver: a stand-in whose slips overload a neighbour runs to its peak as at converged solves",
          "[solve][interacting][event][heavy]") {
  // The stand-in P3.09N at ε = 0.58 (a fit's trial point): a slip's large force drop drives a
  // neighbour toward φ = 1, where its own compliance grows without bound and the chord iteration
  // cannot follow; before, the run stopped there with a solver error (X = 2.37e-4 m). Truth: the
  // same run at converged solves (1e-12). Whether the chord iteration overshoots past φ = 1 on
  // the way (and the junction is then slipped as Overloaded) depends on the last bits of C and
  // of the kernels, so it is reported, not asserted; the designed pair above asserts the slip.
  // Measured: Q_s 3.4e-9, A_s 1.9e-12, t_peak 8.3e-11 relative apart, 2,558 slips each.
  Scene s = load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P3.09N.yaml",
                       {"model.interactions=elastic", "model.alpha_b=7.07107e-16", "model.epsilon=0.581667",
                        "model.eta=94.8683", "stop.at_first_peak=true", "stop.time=13"});
  s.output.series.clear();
  auto run = [](const Scene& scene, std::int64_t& overloaded) {
    const Problem problem = make_problem(scene);
    Recorder rec = make_recorder(scene);
    InteractingEventStepper stepper(problem);
    const RunInfo info = integrate(stepper, problem, rec);
    overloaded = stepper.junctions().work().overloaded;
    return std::make_pair(rec.first_peak().max, info.stats.slips);
  };
  std::int64_t caught = 0, caught_converged = 0;
  const auto [peak, slips] = run(s, caught);
  Scene converged = s;
  converged.solver.interaction_tolerance = 1e-12;
  const auto [peak_c, slips_c] = run(converged, caught_converged);
  INFO("junctions slipped as driven past phi = 1: " << caught << " and " << caught_converged);
  CHECK(slips == slips_c);
  CHECK_THAT(peak.Q, WithinRel(peak_c.Q, 1e-8));
  CHECK_THAT(peak.A, WithinRel(peak_c.A, 1e-8));
  CHECK_THAT(peak.t, WithinRel(peak_c.t, 1e-8));
}
