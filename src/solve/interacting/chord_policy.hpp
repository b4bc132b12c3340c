#pragma once
// The chord iteration's rules (ChordSolver's exact solves, docs/model.md §8): when a
// solve stops, when its passes count as slow, and when the slow passes have cost enough to pay
// for a rebuild of G at the current compliances (a Newton step). Plain data and pure functions:
// the iteration keeps the counts, the policy only judges them.
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace asperity {

struct ChordPolicy {
  double tol;  // of the slip forces: solver.interaction_tolerance, or a solve's own

  // From this pass on, an iterate past φ = 1, or over a threshold while its change is still above
  // stuck(), is a junction far over its threshold (a solve normally ends in 2-9 passes, about 20
  // with refreshes).
  static constexpr int kOverloadCheckFrom = 30;
  static constexpr int kMaxIterations = 200;  // then the solve fails
  static constexpr int kMaxRefreshes = 5;     // rebuilds within one solve

  // Still far from any fixed point: 1e-2 of the slip forces, or 100 times the tolerance if less.
  double stuck() const { return std::min(100 * tol, 1e-2); }

  // Converged: the last change within the tolerance. The solves' errors reach the observables
  // damped (docs/interactions.md, "The interaction tolerance").
  bool within_tolerance(double change) const { return change <= tol; }
  // Contracting by ρ, the iterate is about ρ/(1 − ρ) times the last change from the fixed point:
  // stop when that is already within the tolerance (one pass fewer; never above ten times it off).
  bool within_by_rate(int iter, double change, double previous) const {
    if (!(iter >= 3 && change <= 10 * tol && change < 0.5 * previous)) return false;
    const double rho = change / previous;
    return change * rho / (1.0 - rho) <= tol;
  }
  // Stalled at rounding: the change stops shrinking once it is of the order of the rounding of
  // the sums (about 1e-11 of the slip force; at a looser tolerance the solve has stopped before,
  // so this never ends one early).
  bool stalled(int iter, double change, double previous) const {
    return iter >= 3 && change < std::min(10 * tol, 1e-11) && change > 0.5 * previous;
  }
  bool converged(int iter, double change, double previous) const {
    return within_tolerance(change) || within_by_rate(iter, change, previous) || stalled(iter, change, previous);
  }

  // Slow: contracting by more than 0.2 a pass, or by more than 0.5 within ten times the tolerance
  // (where within_by_rate cannot stop it yet): the reference compliances drifted from the
  // junctions' own.
  bool slow(int iter, double change, double previous) const {
    return iter >= 3 && ((change > 0.2 * previous && change > 10 * tol) || (change > 0.5 * previous && change > tol));
  }
  // A rebuild costs about n/8 passes over G (O(n³) against O(n²)), so the slow passes since the
  // last rebuild are paid until they add up to one (a rent-or-buy rule: at most twice the better
  // of the two), unless this solve grows or runs long.
  static bool rebuild_worth(std::int64_t slow_passes, std::size_t n, double change, double previous, int iter) {
    return slow_passes * 8 >= static_cast<std::int64_t>(n) || change > previous || iter >= 20;
  }
};

}  // namespace asperity
