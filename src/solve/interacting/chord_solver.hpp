#pragma once
// The exact solves of an interacting population's pinned set (docs/model.md §8, the fast solver):
// at slider position X, f = X a0 + b0 − G Δ(f) by the chord iteration, warm-started from the
// solves before it, stopped and rebuilt by ChordPolicy's rules. The solver owns what the solves
// need and change: the pinned operator (G, a0, b0; any PinnedOperator), the junctions' own
// nonlinear law (with its warm starts), the cache of solves between events and its interpolants,
// the seeds a slip leaves, the deadline and the work counters. InteractingJunctions owns the
// junctions' states and the events, and tells the solver when the pinned set changes.
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
#include "solve/interacting/chord_policy.hpp"
#include "solve/interacting/eq3_displacement.hpp"
#include "solve/interacting/force_cache.hpp"
#include "solve/interacting/pinned_compliance.hpp"
#include "solve/interacting/pinned_operator.hpp"

namespace asperity {

class Anderson;

// The chord iteration drove the junction at position q far over its slip force: past φ = 1
// (where u' grows without bound and the iteration cannot follow it to the root just below 1),
// or over its threshold while the iteration, long past its usual passes, cannot settle (a
// step-limited cycle between two states over it). Such a junction is over its threshold: inside
// an avalanche the junction set slips it (the most overloaded by the iterate); anywhere else it
// is the SolverError it derives from.
struct OverloadedJunction : SolverError {
  OverloadedJunction(const std::string& what, std::size_t position) : SolverError(what), q(position) {}
  std::size_t q;
};

template <PinnedOperator Op>
class ChordSolver {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  // Every junction of J pinned. J is read (thresholds, stiffnesses, areas) and must outlive the
  // solver; nonlinear_law: the junctions' areas follow their forces (Eq. 3). single_from: N from
  // which the operator may keep a single-precision copy (PinnedCompliance). Throws SolverError
  // when the universal law's table cannot reach the needed accuracy.
  ChordSolver(const Problem& problem, const JunctionState& J, bool nonlinear_law, std::size_t single_from);
  ChordSolver(const ChordSolver&) = delete;
  ChordSolver& operator=(const ChordSolver&) = delete;

  const Op& pinned() const { return pinned_; }
  double tolerance() const { return tol_; }  // solver.interaction_tolerance, of the slip forces
  double threshold(std::size_t q) const;     // N, the slip force of position q
  // Own displacement u(f) [m] and du/df [m/N] of the junction at position q (not const: the
  // nonlinear law keeps its warm start).
  void own(std::size_t q, double f, double& u, double& du);

  // Exact solve at X, warm-started: a new node (not cached), converged to `tol` of the slip forces
  // (the solver's tolerance unless given).
  ForceNode solve(double X) { return solve(X, tol_); }
  ForceNode solve(double X, double tol);
  // The cache of solves of the current set: the node at X (solved if needed), all nodes, their
  // refinement, and F(X) or A(X) from its interpolants (ForceCache::value).
  const ForceNode& at(double X) { return cache_.at(X); }
  const std::vector<ForceNode>& nodes() const { return cache_.nodes(); }
  void refine() { cache_.refine(); }
  double value(double X, double ForceNode::*v, double ForceNode::*slope, double x_up, double x_down) {
    return cache_.value(X, v, slope, x_up, x_down);
  }
  // The totals' parts outside the pinned set's solve: the slipping junctions' forces [N], the
  // areas that do not follow a force [m²].
  double slipping_force() const { return F_slip_; }
  double frozen_area() const { return A_fixed_; }
  // Right after a slip at X: the new set's d²f/dX² there, by position (null: not known).
  const std::vector<double>* curvatures_at(double X) const;

  // The junction at position q slips at X, carrying f_slip [N] from now on; its frozen area
  // [m²] counts in the totals when its area followed its force. The new set's seed at X is
  // predicted from the cached solves (the old set's), then the cache is cleared.
  void slip(std::size_t q, double f_slip, double frozen_area_m2, double X);
  // Slipping junction j joins the pinned set at force f [N] (nonlinear: its area follows its
  // force from now on, and its frozen area leaves the totals); returns its own displacement u(f)
  // [m]. After the last, repinned() with every junction's anchor.
  double repin(std::size_t j, bool nonlinear, double f, double frozen_area_m2);
  void repinned(const std::vector<double>& anchor_m);

  // From the deadline on, a chord pass throws WallTimeReached (see InteractingJunctions). Starts
  // as the problem's stop.wall_time from construction; set_deadline only brings it closer.
  void set_deadline(std::chrono::steady_clock::time_point deadline) { deadline_ = std::min(deadline_, deadline); }
  void clear_deadline() { deadline_ = std::chrono::steady_clock::time_point::max(); }
  bool past_deadline() const { return std::chrono::steady_clock::now() >= deadline_; }

  // Work done, for benchmarks: exact solves, their chord iterations, and the wall time [s] of
  // the junctions' own laws and of the iterate's updates (per junction).
  std::int64_t solves() const { return solves_; }
  std::int64_t iterations() const { return iterations_; }
  double law_seconds() const { return teams_.laws.seconds(); }
  double update_seconds() const { return teams_.updates.seconds(); }

 private:
  // The steps of a solve's chord iteration, on the work vectors of one solve: from node's warm
  // start to the fixed point at X (returns the passes); its start; the junctions' own laws at
  // the iterate; the chord map's image (one pass over G); the damped or accelerated step
  // (returns the largest change, of the slip forces); a rebuild of G at the current compliances.
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
  // Throws OverloadedJunction when an iterate f (per position) puts a junction past φ = 1, or
  // over its threshold while the iteration's last change is still above `stuck`.
  void overloaded_check(double X, const std::vector<std::size_t>& active, const std::vector<double>& f, double change,
                        double stuck) const;
  // The iteration's start at X: f and df/dX per position of P (see the .cpp).
  void warm_start(double X, std::vector<double>& f, std::vector<double>& a) const;
  // The new set's seed at X after position q slips with f_slip: at_X, the old set's solution
  // nearest X (or null); other, at_X's neighbour in the old cache (or null), for the curvatures.
  void predict_seed(std::size_t q, double f_slip, const ForceNode* at_X, const ForceNode* other, double X);

  const JunctionState& J_;
  double tol_;
  Eq3Displacement eq3_;
  // G, D, a0, b0 change with the reference compliances, a choice of the iteration, not of the
  // solution: refreshed inside solves. The cache is a memo of the solves.
  Op pinned_;
  ForceCache cache_;
  double F_slip_ = 0, A_fixed_ = 0;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::vector<double> last_f_, last_a_;  // by junction: the last solve (warm start)
  // After a slip at seed_X_: the new set's forces and slopes there, predicted (warm start).
  bool seed_valid_ = false;
  double seed_X_ = 0;
  std::vector<double> seed_f_, seed_a_, seed_c_;  // c: d²f/dX² (empty: unknown)
  double seed_h_ = 0;                             // m: the spacing of the old nodes the curvatures come from
  std::int64_t solves_ = 0, iterations_ = 0;
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

extern template class ChordSolver<PinnedCompliance>;

}  // namespace asperity
