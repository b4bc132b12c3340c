// solve/interacting/chord_solver.hpp alone: its solves meet the pinned set's equations
// u_i(f_i) + Σ_j C_ij f_j = X − x_i (C from interaction_matrix, u from a second Eq3Displacement:
// neither is the solver's G), before and after junctions slip (then f_j is the slipping force for
// the slipped), and its totals add the slipped junctions' forces and frozen areas; a second
// PinnedOperator gives the same solves through it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../bench/probes/krylov_operator.hpp"
#include "physics/interface_law.hpp"
#include "scene/load.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/chord_solver.hpp"
#include "solve/interacting/chord_solver_impl.hpp"
#include "solve/interacting/eq3_displacement.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "solve/interacting/pinned_compliance.hpp"

using namespace asperity;

namespace {

static_assert(PinnedOperator<PinnedCompliance>);

// The stand-in P0.98N (STAND-IN data) with elastic interactions; alpha_b > 0: every junction's
// own law is Eq. (3)'s nonlinear one.
Problem stand_in(const std::string& tolerance) {
  return make_problem(load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P0.98N.yaml",
                                 {"model.interactions=elastic", "solver.interaction_tolerance=" + tolerance}));
}

// max over pinned junctions of |u_i(f_i) + Σ_j C_ij f_j − X| / (threshold_i / k_i): the equations'
// residual as a force error relative to the slip force (1/k_i, the junction's own compliance at
// zero force, turns displacement into force). f: every junction's force (the slipping ones'
// constant force included).
double residual(const Problem& p, const JunctionState& J, const ChordSolver<PinnedCompliance>& s, Eq3Displacement& eq3,
                const InteractionMatrix& C, const std::vector<double>& f, double X) {
  double worst = 0;
  const PinnedCompliance& P = s.pinned();
  for (std::size_t q = 0; q < P.size(); ++q) {
    const std::size_t i = P.junction(q);
    double u, du;
    eq3.at(i, f[i], u, du);
    double coupled = 0;
    for (std::size_t j = 0; j < p.size(); ++j) coupled += C(i, j) * f[j];
    worst = std::max(worst, std::abs(u + coupled - X) * J.k[i] / s.threshold(q));
  }
  return worst;
}

// Every junction's force: the solve's at the pinned positions, `slipping` elsewhere.
std::vector<double> all_forces(const ChordSolver<PinnedCompliance>& s, const ForceNode& node,
                               const std::vector<double>& slipping) {
  std::vector<double> f = slipping;
  for (std::size_t q = 0; q < s.pinned().size(); ++q) f[s.pinned().junction(q)] = node.f[q];
  return f;
}

}  // namespace

TEST_CASE("chord solver: its solves meet the pinned set's equations to their tolerance, before and after slips",
          "[solve][interacting][chord]") {
  for (const std::string text : {"1e-6", "1e-10"}) {
    const double tol = std::stod(text);
    CAPTURE(tol);
    const Problem p = stand_in(text);
    const JunctionState J(p.A0, p.law);
    ChordSolver<PinnedCompliance> s(p, J, true, PinnedCompliance::kSingleFrom);
    Eq3Displacement eq3(p.law, J.A0);
    const InteractionMatrix C = interaction_matrix(p);
    const std::size_t N = p.size();
    std::vector<double> slipping(N, 0.0);

    // X at half the first slip by the linear prediction: every junction below its threshold.
    const ForceNode probe = s.solve(1e-9);
    double X = HUGE_VAL;
    for (std::size_t q = 0; q < N; ++q) X = std::min(X, 1e-9 * s.threshold(q) / probe.f[q]);
    X *= 0.5;
    const ForceNode before = s.solve(X);
    // The solve's contract is its tolerance (ChordPolicy's stopping rule); measured 0.06 tol and
    // 0.12 tol here, 0.8 tol and 0.4 tol after the slips below.
    CHECK(residual(p, J, s, eq3, C, all_forces(s, before, slipping), X) < 2 * tol);
    // Totals: F the sum of the forces; with no slip, no frozen area.
    double F = 0;
    for (const double f : before.f) F += f;
    CHECK(before.F == Approx(F).epsilon(1e-13));
    CHECK(s.frozen_area() == 0.0);

    // Three junctions slip at X (as an avalanche would), each carrying its slipping force.
    double F_slip = 0, A_frozen = 0;
    for (const std::size_t i : {std::size_t{3}, N / 2, N - 1}) {
      const double f_sl = slipping_force(p.law, p.area_law, J.A0[i], J.f_s[i]);
      const double A = contact_at_first_slip(p.law, J.A0[i]).area_m2;
      s.slip(s.pinned().position(i), f_sl, A, X);
      slipping[i] = f_sl;
      F_slip += f_sl, A_frozen += A;
    }
    CHECK(s.pinned().size() == N - 3);
    CHECK(s.slipping_force() == Approx(F_slip).epsilon(1e-14));
    CHECK(s.frozen_area() == Approx(A_frozen).epsilon(1e-14));
    const ForceNode after = s.solve(X);
    CHECK(residual(p, J, s, eq3, C, all_forces(s, after, slipping), X) < 2 * tol);
    double F_after = F_slip;
    for (const double f : after.f) F_after += f;
    CHECK(after.F == Approx(F_after).epsilon(1e-13));
    // The cache answers with the same solve as a fresh one.
    const ForceNode& cached = s.at(X);
    CHECK(cached.F == Approx(after.F).epsilon(4 * tol));
  }
}

TEST_CASE("chord solver: a second pinned operator (CG with the FFT product) gives the dense one's solves",
          "[solve][interacting][chord]") {
  // The probe's matrix-free operator (bench/probes/krylov_operator.hpp; measured slower than the
  // dense G at every size tried, so not in the solver: docs/performance.md) through the same
  // ChordSolver: the concept is all the solver asks of an operator.
  const Problem p = stand_in("1e-10");
  const JunctionState J(p.A0, p.law);
  ChordSolver<PinnedCompliance> dense(p, J, true, PinnedCompliance::kSingleFrom);
  ChordSolver<KrylovPinnedOperator> krylov(p, J, true, 0);
  const std::size_t N = p.size();
  const ForceNode probe = dense.solve(1e-9);
  double X = HUGE_VAL;
  for (std::size_t q = 0; q < N; ++q) X = std::min(X, 1e-9 * dense.threshold(q) / probe.f[q]);
  X *= 0.5;
  const auto difference = [&](const ForceNode& a, const ForceNode& b) {
    double worst = 0;
    for (std::size_t q = 0; q < dense.pinned().size(); ++q) {
      const std::size_t qk = krylov.pinned().position(dense.pinned().junction(q));
      worst = std::max(worst, std::abs(a.f[q] - b.f[qk]) / dense.threshold(q));
    }
    return worst;
  };
  // Within the FFT product's own error (1–4e-9 of a product), not the tolerance 1e-10: measured
  // 3.5e-9 of the slip force here and 9.0e-9 after the slips.
  CHECK(difference(dense.solve(X), krylov.solve(X)) < 3e-8);
  for (const std::size_t i : {std::size_t{3}, N / 2, N - 1}) {
    const double f_sl = slipping_force(p.law, p.area_law, J.A0[i], J.f_s[i]);
    const double A = contact_at_first_slip(p.law, J.A0[i]).area_m2;
    dense.slip(dense.pinned().position(i), f_sl, A, X);
    krylov.slip(krylov.pinned().position(i), f_sl, A, X);
  }
  CHECK(difference(dense.solve(X), krylov.solve(X)) < 3e-8);
}
