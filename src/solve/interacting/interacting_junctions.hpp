#pragma once
// Interacting junctions as the event method sees them (docs/model.md §8, the fast solver): the same
// interface as EventJunctions (force(X), area(X), slip positions above and below X,
// slip_crossed, repin_all), so EventIntegrator runs them unchanged.
//
// The pinned set P obeys, for i ∈ P,  u_i(f_i) + Σ_{j∈P, j≠i} C_ij f_j = X − h_i,  with u_i the
// junction's own displacement at force f_i (f/k, or Eq. (3)'s nonlinear form for a junction
// whose area follows its force) and h_i = x_i + Σ_{j slipping} C_ij f_j. With M = D + C_PP, D
// a diagonal reference compliance (u_i' at some force; exact for linear junctions),
//   f = X a0 + b0 − G Δ(f),   G = M⁻¹, a0 = G 1, b0 = −G h,  Δ_i(f) = u_i(f_i) − D_i f_i,
// exact for linear junctions (Δ = 0, no iteration) and a contraction for the nonlinear ones
// (a chord iteration whose rate is the drift of u_i' from D_i; when it slows, D is reset to the
// current u' and G rebuilt: a Newton step). G is kept explicitly and updated when one junction
// changes state: a slip removes its row and column (rank-one, O(N²)); a repin, and every N
// rank-one updates (rounding), rebuild G (LAPACK Cholesky inverse in place). Memory: C and G in
// one buffer of N² doubles, from N = 2,048 G's single-precision copy (N²/2 floats: the passes
// that can, read half the bytes), plus O(N) vectors.
//
// Between events the total force F(X) and area A(X) are smooth functions of X alone: while
// nonlinear junctions remain, they are piecewise cubic Hermite interpolants on nodes where the
// system is solved exactly (with dF/dX from the differentiated system), refined until each
// piece's estimated error is below the tolerance; linear-only populations have F = X Σa0 + Σb0 + F_slip
// exactly. The slip positions are found by Newton in X on the exact solutions.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/chord_solver.hpp"
#include "solve/interacting/force_cache.hpp"
#include "solve/interacting/pinned_compliance.hpp"

namespace asperity {

// The jobs are split: ChordSolver runs the exact solves of the pinned set (with the operator G
// and the load vectors, the junctions' own nonlinear law, the cache of solves between events and
// their interpolants); this class keeps the junctions' states and runs the events (slip
// positions, avalanches, repins).
class InteractingJunctions {
 public:
  // Throws SolverError when the universal law's table cannot reach the needed accuracy.
  // single_from: N from which chord passes may read G's single-precision copy within a tenth of
  // the interaction tolerance (PinnedCompliance; tests lower it).
  explicit InteractingJunctions(const Problem& problem, std::size_t single_from = PinnedCompliance::kSingleFrom);
  InteractingJunctions(const InteractingJunctions&) = delete;
  InteractingJunctions& operator=(const InteractingJunctions&) = delete;

  // Not const: each solves at X when its interpolants do not yet cover it (and caches the node).
  double force(double X);  // total junction force at slider position X [N]
  double area(double X);   // total area [m²]
  bool has_threshold() const;
  double next_threshold() const { return x_up_; }  // m: the next slip as X grows
  bool has_threshold_below() const;
  double next_threshold_below() const { return x_down_; }  // m: the next slip as X decreases
  std::int64_t n_slipping() const { return static_cast<std::int64_t>(N_ - solver_.pinned().size()); }
  std::int64_t n_intact() const { return n_intact_; }
  std::int64_t force_evals() const { return force_evals_; }
  std::int64_t slips() const { return slips_; }
  std::int64_t repins() const { return repins_; }

  // The junction whose threshold was reached slips, then every pinned junction at or over its
  // threshold at the same X, one at a time (an avalanche at fixed X); returns how many slipped.
  std::int64_t slip_crossed(double X);
  // All slipping junctions repin at X, with no force jump.
  void repin_all(double X);
  // From the deadline on, a chord pass, or an avalanche that would slip one more junction (after
  // at least one slip of the event), throws WallTimeReached instead: at large N one solver step
  // (its solves, their rebuilds, an avalanche) can take minutes to hours, and so can the first
  // event search in the constructor. The deadline starts as the problem's stop.wall_time from
  // construction; set_deadline only brings it closer, clear_deadline removes it.
  void set_deadline(std::chrono::steady_clock::time_point deadline) { solver_.set_deadline(deadline); }
  void clear_deadline() { solver_.clear_deadline(); }

  // Every junction's force at X (N, by junction) for the current pinned set; for tests and
  // the force-spread study.
  std::vector<double> forces(double X);
  const JunctionState& state() const { return J_; }  // areas, thresholds, pinned, intact
  // f_i / (σ A_i) at X, A_i the current area (Eq. 3 at f_i for a junction whose area follows its
  // force): 1 at the slip threshold, ε for a slipping junction under area_law until_first_slip.
  std::vector<double> load_ratios(double X);
  // Every junction's contact area [m²] with the forces f (N, by junction, as forces() gives them
  // for the current set): Eq. (3) at f_i for a junction whose area follows its force, else its
  // frozen area.
  std::vector<double> areas(const std::vector<double>& f) const;

  // Work done, for benchmarks: exact solves, their chord iterations, rank-one updates, rebuilds;
  // overloaded: junctions slipped in an avalanche because the chord iteration drove them past
  // φ = 1 (see Overloaded).
  struct Work {
    std::int64_t solves = 0, iterations = 0, rank_one = 0, rebuilds = 0, overloaded = 0;
    std::int64_t single_passes = 0, single_refreshes = 0;  // chord passes on G's single-precision copy
    // Wall time by phase [s]: passes over G (exact and on the copy, with the removals kept
    // aside), folds of removals into G (and the copy's rewrites), rebuilds (LAPACK), the rest of
    // the removals, the junctions' own laws and the iterate's updates (per junction).
    double pass_s = 0, fold_s = 0, rebuild_s = 0, remove_s = 0, law_s = 0, update_s = 0;
  };
  Work work() const;

 private:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  ForceNode solve(double X) { return solver_.solve(X); }
  double threshold(std::size_t q) const { return solver_.threshold(q); }  // N, position q
  const PinnedCompliance& pinned() const { return solver_.pinned(); }
  void after_change(double X);  // new event point: node, thresholds
  // Junction k (npos: none) slips at X, then every pinned one at or over its threshold, one at a
  // time, most overloaded first; then the new slip positions. Returns how many slipped.
  std::int64_t settle(double X, std::size_t k);
  void find_thresholds(double X);
  // From the crossing of position k predicted at X + dir·best: Newton in X on its force, then on
  // any junction found over its threshold before it, the earliest first; returns the slip
  // position and leaves k on the position that slips there.
  double refine_crossing(double X, int dir, double best, std::size_t& k);
  void start_slip(std::size_t i, double X);

  const ContactLaw& law_;
  AreaLaw area_law_;
  bool nonlinear_law_;
  std::size_t N_ = 0;
  JunctionState J_;
  ChordSolver<PinnedCompliance> solver_;  // reads J_: constructed after it
  double sum_a0_ = 0, sum_b0_ = 0;        // of the pinned set: F = X Σa0 + Σb0 + F_slip when all are linear
  std::int64_t n_intact_ = 0, slips_ = 0, repins_ = 0, overloaded_ = 0;
  double x_up_ = 0, x_down_ = 0;
  std::size_t k_up_ = npos, k_down_ = npos;  // junctions of the next slips
  std::int64_t force_evals_ = 0;
};

}  // namespace asperity
