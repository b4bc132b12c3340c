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

#include "solve/core/adaptive_team.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"
#include "solve/interacting/anderson.hpp"
#include "solve/interacting/chord_policy.hpp"
#include "solve/interacting/eq3_displacement.hpp"
#include "solve/interacting/force_cache.hpp"
#include "solve/interacting/pinned_compliance.hpp"

namespace asperity {

// The jobs are split: PinnedCompliance keeps G and the load vectors of the pinned set,
// Eq3Displacement the junctions' own nonlinear law, ForceCache the exact solves between events
// and their interpolants; this class runs the chord iteration (solve) and the events (slip
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
  std::int64_t n_slipping() const { return static_cast<std::int64_t>(N_ - pinned_.size()); }
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
  void set_deadline(std::chrono::steady_clock::time_point deadline) { deadline_ = std::min(deadline_, deadline); }
  void clear_deadline() { deadline_ = std::chrono::steady_clock::time_point::max(); }

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

  // The chord iteration drove the junction at position q far over its slip force: past φ = 1
  // (where u' grows without bound and the iteration cannot follow it to the root just below 1),
  // or over its threshold while the iteration, long past its usual passes, cannot settle (a
  // step-limited cycle between two states over it). Such a junction is over its threshold:
  // inside an avalanche settle() slips it (the most overloaded by the iterate); anywhere else it
  // is the SolverError it derives from.
  struct Overloaded : SolverError {
    Overloaded(const std::string& what, std::size_t position) : SolverError(what), q(position) {}
    std::size_t q;
  };

  // Own displacement u(f) [m] and du/df [m/N] of the junction at position q of P.
  void own(std::size_t q, double f, double& u, double& du);
  // Exact solve at X by the chord iteration, warm-started from the cache: a new node, converged to
  // `tol` of the slip forces (solver.interaction_tolerance unless given).
  ForceNode solve(double X) { return solve(X, tol_); }
  ForceNode solve(double X, double tol);
  // The steps of a solve's chord iteration (interacting_solve.cpp), on the work vectors of one
  // solve: from node's warm start to the fixed point at X (returns the passes); its start; the
  // junctions' own laws at the iterate; the chord map's image (one pass over G); the damped or
  // accelerated step (returns the largest change, of the slip forces); a rebuild of G at the
  // current compliances.
  struct ChordPass;
  int chord_iteration(double X, const ChordPolicy& policy, ForceNode& node);
  ChordPass start_chord(double tol) const;
  void own_laws(const ForceNode& node, ChordPass& w);
  void chord_image(double X, const ForceNode& node, ChordPass& w);
  double take_step(double X, double damp, ForceNode& node, const ChordPass& w);
  void refresh_reference(const ForceNode& node, ChordPass& w);
  // One chord iteration's step on the active positions: damps it (returns the factor) or
  // replaces g by Anderson's accelerated iterate when that stays within the same bound.
  double chord_step(double X, const std::vector<std::size_t>& active, double a_scale, const std::vector<double>& y1,
                    const std::vector<double>& y2, const std::vector<double>& z, std::vector<double>& g,
                    Anderson& aa) const;
  void add_totals(ForceNode& node) const;  // F, dF/dX, A, dA/dX of a solved node
  // Throws Overloaded when an iterate f (per position) puts a junction past φ = 1, or over its
  // threshold while the iteration's last change is still above `stuck` (of the slip forces).
  void overloaded_check(double X, const std::vector<std::size_t>& active, const std::vector<double>& f, double change,
                        double stuck) const;
  // The iteration's start at X: f and df/dX per position of P (see the .cpp).
  void warm_start(double X, std::vector<double>& f, std::vector<double>& a) const;
  double threshold(std::size_t q) const;  // N, the slip force of position q
  void after_change(double X);            // new event point: node, thresholds
  // Junction k (npos: none) slips at X, then every pinned one at or over its threshold, one at a
  // time, most overloaded first; then the new slip positions. Returns how many slipped.
  std::int64_t settle(double X, std::size_t k);
  void find_thresholds(double X);
  // From the crossing of position k predicted at X + dir·best: Newton in X on its force, then on
  // any junction found over its threshold before it, the earliest first; returns the slip
  // position and leaves k on the position that slips there.
  double refine_crossing(double X, int dir, double best, std::size_t& k);
  // Position q leaves P carrying f_slip; at_X: the old set's solution nearest X (or null), from
  // which the new set's seed at X is predicted.
  // other: at_X's neighbour in the old cache (or null), for the curvatures.
  void remove_pinned(std::size_t q, double f_slip, const ForceNode* at_X, const ForceNode* other, double X);
  void start_slip(std::size_t i, double X);

  const Problem& p_;
  const ContactLaw& law_;
  AreaLaw area_law_;
  bool nonlinear_law_;
  double tol_;  // solver.interaction_tolerance: of the slip force, per solve and slip position
  std::size_t N_ = 0;
  JunctionState J_;
  Eq3Displacement eq3_;
  // G, D, a0, b0 change with the reference compliances, a choice of the iteration, not of the
  // solution: refreshed inside solves. The cache is a memo of the solves.
  PinnedCompliance pinned_;
  ForceCache cache_;
  double sum_a0_ = 0, sum_b0_ = 0, F_slip_ = 0, A_fixed_ = 0;
  std::int64_t n_intact_ = 0, slips_ = 0, repins_ = 0, overloaded_ = 0;
  double x_up_ = 0, x_down_ = 0;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::size_t k_up_ = npos, k_down_ = npos;  // junctions of the next slips
  std::vector<double> last_f_, last_a_;      // by junction: the last solve (warm start)
  // After a slip at seed_X_: the new set's forces and slopes there, predicted (warm start).
  bool seed_valid_ = false;
  double seed_X_ = 0;
  std::vector<double> seed_f_, seed_a_, seed_c_;  // c: d²f/dX² (empty: unknown)
  double seed_h_ = 0;                             // m: the spacing of the old nodes the curvatures come from
  std::int64_t force_evals_ = 0, solves_ = 0, iterations_ = 0;
  // Chord passes that contracted slowly since G was last rebuilt (rebuild count slow_since_).
  std::int64_t slow_passes_ = 0, slow_since_ = -1;
  // The threads of the per-junction loops of a chord pass (the laws; the iterate's update), chosen
  // by measuring them (adaptive_team.hpp); from 512 junctions on two threads pay on a quiet machine.
  struct Teams {
    explicit Teams(int threads) : laws(threads, 512), updates(threads, 512) {}
    AdaptiveTeam laws, updates;
  };
  Teams teams_;
};

}  // namespace asperity
