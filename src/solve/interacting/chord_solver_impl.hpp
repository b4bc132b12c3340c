#pragma once
// ChordSolver's definitions (chord_solver.hpp), for any PinnedOperator: the pinned set's exact
// solves (docs/model.md §8), the chord iteration at one slider position, warm-started from the
// cache, its steps, and the totals of a solved node; the changes of the set. The rules that stop
// the iteration and rebuild G are ChordPolicy's. chord_solver.cpp instantiates it for
// PinnedCompliance; another operator's user includes this file.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "physics/interface_law.hpp"
#include "solve/core/run_limits.hpp"
#include "solve/interacting/anderson.hpp"
#include "solve/interacting/chord_policy.hpp"
#include "solve/interacting/chord_solver.hpp"
#include "solve/interacting/solver_failure.hpp"

namespace asperity {

namespace chord_detail {

// u'(0) = 1/k0 for both kinds of junction: the first reference compliances.
inline std::vector<double> initial_reference(const JunctionState& J) {
  std::vector<double> D(J.k.size());
  for (std::size_t i = 0; i < D.size(); ++i) D[i] = 1.0 / J.k[i];
  return D;
}

}  // namespace chord_detail

template <PinnedOperator Op>
ChordSolver<Op>::ChordSolver(const Problem& problem, const JunctionState& J, bool nonlinear_law,
                             std::size_t single_from)
    : J_(J),
      tol_(problem.solver.interaction_tolerance),
      eq3_(nonlinear_law ? Eq3Displacement(problem.law, J.A0) : Eq3Displacement()),
      pinned_(problem, chord_detail::initial_reference(J), nonlinear_law, single_from),
      cache_([this](double X) { return solve(X); }, 0.1 * problem.solver.tolerance),
      teams_(omp_get_max_threads()) {
  const std::size_t N = J.A0.size();
  if (!nonlinear_law)
    for (std::size_t i = 0; i < N; ++i) A_fixed_ += J.A0[i];
  last_f_.assign(N, 0.0);
  last_a_.assign(N, 0.0);
  // The first event search counts: at large N its solves and rebuilds alone can outlast a limit
  // (docs/performance.md, "Interacting solver", the N = 20,000 runs).
  deadline_ = wall_deadline(problem.limits);
}

template <PinnedOperator Op>
double ChordSolver<Op>::threshold(std::size_t q) const {
  const std::size_t i = pinned_.junction(q);
  // Eq. (3) junctions slip at f = σ A(f), φ = φ_s; the others at σ times their frozen area.
  return pinned_.nonlinear(q) ? eq3_.slip_force(i) : J_.f_s[i];
}

template <PinnedOperator Op>
void ChordSolver<Op>::own(std::size_t q, double f, double& u, double& du) {
  const std::size_t i = pinned_.junction(q);
  if (pinned_.nonlinear(q)) return eq3_.at(i, f, u, du);
  u = f / J_.k[i];
  du = 1.0 / J_.k[i];
}

template <PinnedOperator Op>
const std::vector<double>* ChordSolver<Op>::curvatures_at(double X) const {
  return seed_valid_ && seed_X_ == X && seed_c_.size() == pinned_.size() ? &seed_c_ : nullptr;
}

template <PinnedOperator Op>
void ChordSolver<Op>::slip(std::size_t q, double f_slip, double frozen_area_m2, double X) {
  if (pinned_.nonlinear(q)) A_fixed_ += frozen_area_m2;
  F_slip_ += f_slip;
  // The old set's solution nearest X (the slip position's node: X is its event, located to the
  // integrator's resolution), from which the new set's seed at X is predicted.
  const ForceNode* near = nullptr;
  for (const ForceNode& m : cache_.nodes())
    if (!near || std::abs(m.X - X) < std::abs(near->X - X)) near = &m;
  // The node farthest from it (the last Newton iterates sit within rounding of each other, too
  // close for a second difference): with it, the per-junction curvature at X.
  const ForceNode* other = nullptr;
  for (const ForceNode& m : cache_.nodes())
    if (near && (!other || std::abs(m.X - near->X) > std::abs(other->X - near->X))) other = &m;
  predict_seed(q, f_slip, near, other, X);
  pinned_.remove(q, f_slip);
  cache_.clear();
}

template <PinnedOperator Op>
double ChordSolver<Op>::repin(std::size_t j, bool nonlinear, double f, double frozen_area_m2) {
  const std::size_t q = pinned_.add(j, nonlinear);
  double u, du;
  own(q, f, u, du);
  pinned_.set_reference(q, du);
  if (pinned_.nonlinear(q)) A_fixed_ -= frozen_area_m2;
  return u;
}

template <PinnedOperator Op>
void ChordSolver<Op>::repinned(const std::vector<double>& anchor_m) {
  pinned_.set_anchors(anchor_m);  // nobody slips: h = x
  F_slip_ = 0.0;
  cache_.clear();  // its nodes belong to the old set
  seed_valid_ = false;
  seed_c_.clear();
  pinned_.rebuild();
}

template <PinnedOperator Op>
void ChordSolver<Op>::predict_seed(std::size_t q, double f_sl, const ForceNode* at_X, const ForceNode* other,
                                   double X) {
  const std::size_t n = pinned_.size();
  // The new set's solution at X, to first order: the others take up the slipped junction's
  // force change through column q of G (exact for linear junctions, where Δ = 0; for Eq. (3)
  // junctions off only by the drift of u' from D over the redistribution), from the old
  // solution at X (first order from the node at_X): the seed of the next solve there. Its
  // slopes likewise, the slipping force being constant.
  seed_valid_ = at_X != nullptr;
  if (seed_valid_) {
    const std::vector<double> g = pinned_.row(q);
    const double gqq = g[q];
    seed_X_ = X;
    seed_f_.resize(n);
    seed_a_.resize(n);
    const double dX = X - at_X->X;
    const double df = f_sl - (at_X->f[q] + at_X->a[q] * dX), da = -at_X->a[q];
    for (std::size_t r = 0; r < n; ++r) {
      seed_f_[r] = at_X->f[r] + at_X->a[r] * dX + g[r] / gqq * df;
      seed_a_[r] = at_X->a[r] + g[r] / gqq * da;
    }
    // Curvatures d²f/dX² at X: the old set's, from the cubic Hermite of at_X and its neighbour,
    // redistributed like the slopes (the slipping force's is zero). They make the first solve
    // away from X (Newton on the next slip position) start at second order instead of first.
    seed_c_.clear();
    if (other && other->X != at_X->X && other->f.size() == n) {
      const bool right = at_X->X > other->X;  // at_X is the piece's right end
      const ForceNode& a = right ? *other : *at_X;
      const ForceNode& b = right ? *at_X : *other;
      const double h = b.X - a.X;
      seed_h_ = h;
      seed_c_.resize(n);
      for (std::size_t r = 0; r < n; ++r) {
        const double c2 = 3 * (b.f[r] - a.f[r]) - h * (2 * a.a[r] + b.a[r]);
        const double c3 = 2 * (a.f[r] - b.f[r]) + h * (a.a[r] + b.a[r]);
        seed_c_[r] = (2 * c2 + (right ? 6 * c3 : 0.0)) / (h * h);
      }
      const double dc = -seed_c_[q];
      for (std::size_t r = 0; r < n; ++r) seed_c_[r] += g[r] / gqq * dc;
    }
    // The positions as the operator's remove leaves them: the last moves into q.
    if (q != n - 1) seed_f_[q] = seed_f_[n - 1], seed_a_[q] = seed_a_[n - 1];
    seed_f_.pop_back();
    seed_a_.pop_back();
    if (!seed_c_.empty()) {
      if (q != n - 1) seed_c_[q] = seed_c_[n - 1];
      seed_c_.pop_back();
    }
  }
}

template <PinnedOperator Op>
void ChordSolver<Op>::warm_start(double X, std::vector<double>& f, std::vector<double>& a) const {
  const std::size_t n = pinned_.size();
  // Per junction, f and df/dX are smooth between events: the cubic Hermite of the two nodes
  // around X (or of the two nearest on one side, extrapolated no farther than their spacing
  // twice over) starts the iteration within O(h^4) of the solution instead of the first-order
  // prediction's O(h^2); fewer passes over G for the same fixed point (the stopping rule is
  // unchanged). Without two nodes: the nearest node's first-order prediction, then the seed a
  // slip left at this X (the old solution plus the redistribution of the slipped junction's
  // force), then the last solution.
  const std::size_t m = cache_.nodes().size();
  if (m >= 2) {
    auto it = std::lower_bound(cache_.nodes().begin(), cache_.nodes().end(), X,
                               [](const ForceNode& k, double x) { return k.X < x; });
    std::size_t hi = static_cast<std::size_t>(it - cache_.nodes().begin());
    hi = std::clamp<std::size_t>(hi, 1, m - 1);
    const ForceNode& n0 = cache_.nodes()[hi - 1];
    const ForceNode& n1 = cache_.nodes()[hi];
    const double h = n1.X - n0.X;
    const double t = (X - n0.X) / h;
    if (h > 0 && t >= -2.0 && t <= 3.0) {
      for (std::size_t q = 0; q < n; ++q) f[q] = hermite(n0.X, n1.X, n0.f[q], n0.a[q], n1.f[q], n1.a[q], X, &a[q]);
      return;
    }
  }
  if (m >= 1) {
    const ForceNode* near = &cache_.nodes()[0];
    for (const ForceNode& k : cache_.nodes())
      if (std::abs(k.X - X) < std::abs(near->X - X)) near = &k;
    // From the node a slip left, with the curvatures predicted there: second order.
    // (Within twice the old nodes' spacing, where that cubic's curvature holds.)
    const bool curved =
        seed_valid_ && near->X == seed_X_ && seed_c_.size() == n && std::abs(X - near->X) <= 2 * seed_h_;
    for (std::size_t q = 0; q < n; ++q) {
      const double d = X - near->X, c = curved ? seed_c_[q] : 0.0;
      f[q] = near->f[q] + (near->a[q] + 0.5 * c * d) * d;
      a[q] = near->a[q] + c * d;
    }
    return;
  }
  if (seed_valid_ && seed_X_ == X && seed_f_.size() == n) {
    f = seed_f_;
    a = seed_a_;
    return;
  }
  for (std::size_t q = 0; q < n; ++q) {
    f[q] = last_f_[pinned_.junction(q)];
    a[q] = last_a_[pinned_.junction(q)];
  }
}

template <PinnedOperator Op>
ForceNode ChordSolver<Op>::solve(double X, double tol) {
  const std::size_t n = pinned_.size();
  ForceNode node;
  node.X = X;
  node.f.resize(n);
  node.a.resize(n);
  if (pinned_.n_nonlinear() == 0) {
    for (std::size_t q = 0; q < n; ++q) {
      node.f[q] = X * pinned_.a0(q) + pinned_.b0(q);
      node.a[q] = pinned_.a0(q);
    }
  } else {
    warm_start(X, node.f, node.a);
    iterations_ += chord_iteration(X, ChordPolicy{tol}, node);
  }
  add_totals(node);
  for (std::size_t q = 0; q < n; ++q) {
    last_f_[pinned_.junction(q)] = node.f[q];
    last_a_[pinned_.junction(q)] = node.a[q];
  }
  ++solves_;
  return node;
}

// The work vectors of one solve's chord iteration, by position of P (dl, da, y1, y2) or on the
// active positions, forces then slopes, scaled (z, g).
template <PinnedOperator Op>
struct ChordSolver<Op>::ChordPass {
  std::vector<std::size_t> active;  // the nonlinear positions
  std::size_t nA = 0;
  double a_scale = 1;  // the mean |a0| over the active positions
  std::vector<double> dl, da, y1, y2, z, g;
  Anderson aa;
  bool single = false;  // passes may read G's single-precision copy
  typename Op::PassBudget budget;
  explicit ChordPass(std::size_t nA_) : nA(nA_), aa(2 * nA_) {}
};

template <PinnedOperator Op>
int ChordSolver<Op>::chord_iteration(double X, const ChordPolicy& policy, ForceNode& node) {
  const std::size_t n = pinned_.size();
  ChordPass w = start_chord(policy.tol);
  double previous = HUGE_VAL;
  int iter = 0, refreshes = 0;
  for (;;) {
    ++iter;
    // The run's wall-time limit, read at every pass: at large N one step's solves and their
    // Newton refreshes can run minutes past it (docs/performance.md, "Interacting solver").
    if (std::chrono::steady_clock::now() >= deadline_) throw WallTimeReached();
    own_laws(node, w);
    chord_image(X, node, w);
    const double damp = chord_step(X, w.active, w.a_scale, w.y1, w.y2, w.z, w.g, w.aa);
    const double change = take_step(X, damp, node, w);
    // Long after a solve normally ends, an iterate past φ = 1, or over a threshold while still
    // far from any fixed point: a junction far over its threshold, which the iteration cannot
    // follow (see OverloadedJunction; the stand-in P6.40N at α_b = 2.06e-16, ε = 0.503, η = 300 cycled
    // between φ = 0.89 and 0.99 of a junction whose threshold is 0.63).
    if (iter >= ChordPolicy::kOverloadCheckFrom) overloaded_check(X, w.active, node.f, change, policy.stuck());
    if (policy.converged(iter, change, previous)) break;
    // Slow passes since G was last rebuilt, paid until a rebuild at the current compliances is
    // worth it (ChordPolicy::rebuild_worth): the solution is the same, the iteration fast again.
    const bool slow = policy.slow(iter, change, previous);
    if (pinned_.rebuilds() != slow_since_) slow_since_ = pinned_.rebuilds(), slow_passes_ = 0;
    if (slow) ++slow_passes_;
    const bool worth = ChordPolicy::rebuild_worth(slow_passes_, n, change, previous, iter);
    if (slow && worth && refreshes < ChordPolicy::kMaxRefreshes) {
      ++refreshes;
      refresh_reference(node, w);
      previous = HUGE_VAL;
      continue;
    }
    if (iter >= ChordPolicy::kMaxIterations)
      interacting_solver_failure("the chord iteration did not converge in 200 iterations", X);
    previous = change;
  }
  return iter;
}

template <PinnedOperator Op>
typename ChordSolver<Op>::ChordPass ChordSolver<Op>::start_chord(double tol) const {
  const std::size_t n = pinned_.size();
  std::vector<std::size_t> active;
  active.reserve(pinned_.n_nonlinear());
  for (std::size_t q = 0; q < n; ++q)
    if (pinned_.nonlinear(q)) active.push_back(q);
  // Anderson acceleration of the chord map on the active positions' forces and slopes, scaled
  // to O(1) (f by the slip force, df/dX by the mean |a0|). The chord map contracts linearly at
  // the drift of u' from D, almost the same linear map from one iteration to the next, so the
  // last few residuals predict most of the remaining error: fewer passes over G for the same
  // fixed point (the stopping rule is unchanged).
  ChordPass w(active.size());
  w.active = std::move(active);
  const std::size_t nA = w.nA;
  double a_scale = 0;
  for (std::size_t q : w.active) a_scale += std::abs(pinned_.a0(q));
  w.a_scale = nA > 0 && a_scale > 0 ? a_scale / static_cast<double>(nA) : 1.0;
  w.dl.assign(n, 0.0);
  w.da.assign(n, 0.0);
  w.y1.resize(n);
  w.y2.resize(n);
  w.z.resize(2 * nA);
  w.g.resize(2 * nA);
  // A pass may read G's single-precision copy where its error stays within a tenth of the
  // tolerance of each slip force (the fixed point then moves by at most that over 1 − ρ; the
  // stopping rule is unchanged) and within ten times the tolerance of the slopes' mean scale
  // (the slopes only shape the interpolants and Newton's rate; a budget of the tolerance itself
  // held the copy back more often: docs/performance.md, "The copy's budget for the slopes").
  w.single = pinned_.single_kept();
  if (w.single) {
    w.budget.y1.resize(n);
    for (std::size_t q = 0; q < n; ++q) w.budget.y1[q] = 0.1 * tol * threshold(q);
    w.budget.y2 = 10 * tol * w.a_scale;
  }
  return w;
}

template <PinnedOperator Op>
void ChordSolver<Op>::own_laws(const ForceNode& node, ChordPass& w) {
  // The junctions' own laws, each independent of the others (the same numbers on any number of
  // threads): a tenth of a pass's time, worth splitting from a few hundred on.
  const std::size_t nA = w.nA;
  const AdaptiveTeam::Region region(teams_.laws, static_cast<double>(nA));
  const int threads = region.threads();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t k = 0; k < nA; ++k) {
    const std::size_t q = w.active[k];
    double u, du;
    own(q, node.f[q], u, du);
    w.dl[q] = u - pinned_.reference(q) * node.f[q];
    w.da[q] = (du - pinned_.reference(q)) * node.a[q];
  }
}

template <PinnedOperator Op>
void ChordSolver<Op>::chord_image(double X, const ForceNode& node, ChordPass& w) {
  // y = G [Δ, Δ'a]: one pass over the rows of the nonlinear positions.
  if (w.single)
    pinned_.apply(w.active, w.dl, w.da, w.y1, w.y2, w.budget);
  else
    pinned_.apply(w.active, w.dl, w.da, w.y1, w.y2);
  // The chord map's image g and the current iterate z, scaled, on the active positions. This
  // loop and the update (take_step) are per junction (and a maximum), the same numbers on any
  // number of threads; split like the laws (on two threads the other thread otherwise waits
  // through them).
  const std::size_t nA = w.nA;
  const double a_scale = w.a_scale;
  const AdaptiveTeam::Region region(teams_.updates, static_cast<double>(nA));
  const int threads = region.threads();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t k = 0; k < nA; ++k) {
    const std::size_t q = w.active[k];
    const double thr = threshold(q);
    w.z[k] = node.f[q] / thr;
    w.g[k] = (X * pinned_.a0(q) + pinned_.b0(q) - w.y1[q]) / thr;
    w.z[nA + k] = node.a[q] / a_scale;
    w.g[nA + k] = (pinned_.a0(q) - w.y2[q]) / a_scale;
  }
}

template <PinnedOperator Op>
double ChordSolver<Op>::take_step(double X, double damp, ForceNode& node, const ChordPass& w) {
  const std::size_t n = pinned_.size(), nA = w.nA;
  const double a_scale = w.a_scale;
  double change = 0;
  for (std::size_t q = 0; q < n; ++q) {
    if (pinned_.nonlinear(q)) continue;
    const double f = node.f[q] + damp * (X * pinned_.a0(q) + pinned_.b0(q) - w.y1[q] - node.f[q]);
    change = std::max(change, std::abs(f - node.f[q]) / threshold(q));
    node.f[q] = f;
    node.a[q] = pinned_.a0(q) - w.y2[q];
  }
  const AdaptiveTeam::Region region(teams_.updates, static_cast<double>(nA));
  const int threads = region.threads();
#pragma omp parallel for schedule(static) reduction(max : change) num_threads(threads) if (threads > 1)
  for (std::size_t k = 0; k < nA; ++k) {
    const std::size_t q = w.active[k];
    const double thr = threshold(q);
    const double f = thr * (w.z[k] + damp * (w.g[k] - w.z[k]));
    change = std::max(change, std::abs(f - node.f[q]) / thr);
    node.f[q] = f;
    node.a[q] = a_scale * w.g[nA + k];
  }
  return change;
}

template <PinnedOperator Op>
void ChordSolver<Op>::refresh_reference(const ForceNode& node, ChordPass& w) {
  // The reference compliances at the current forces, and G rebuilt (a Newton step's Jacobian).
  for (std::size_t q : w.active) {
    double u, du;
    own(q, node.f[q], u, du);
    pinned_.set_reference(q, du);
  }
  pinned_.rebuild();
  w.aa.clear();
}

template <PinnedOperator Op>
void ChordSolver<Op>::overloaded_check(double X, const std::vector<std::size_t>& active, const std::vector<double>& f,
                                       double change, double stuck) const {
  std::size_t worst = npos;
  double ratio = 0, phi_max = 0;
  for (std::size_t q : active) {
    phi_max = std::max(phi_max, eq3_.force_scale(pinned_.junction(q)) * f[q]);
    if (f[q] / threshold(q) > ratio) ratio = f[q] / threshold(q), worst = q;
  }
  if (worst == npos || !(phi_max >= 1.0 || (ratio > 1.0 && change > stuck))) return;
  char what[240];
  std::snprintf(what, sizeof what,
                "interacting event solver: a pinned junction is driven past its slip force (%.3g times it, phi up "
                "to %.3g) and the coupled solve cannot settle, outside an avalanche, at X = %.6g m",
                ratio, phi_max, X);
  throw OverloadedJunction(what, worst);
}

template <PinnedOperator Op>
double ChordSolver<Op>::chord_step(double X, const std::vector<std::size_t>& active, double a_scale,
                                   const std::vector<double>& y1, const std::vector<double>& y2,
                                   const std::vector<double>& z, std::vector<double>& g, Anderson& aa) const {
  const std::size_t nA = active.size();
  // Damped: no nonlinear junction's φ = s f moves by more than 0.1 in one iteration (far
  // from the solution, e.g. a poor warm start, the full step can overshoot into φ → 1).
  // The accelerated step is taken only where the plain one needs no damping and stays
  // within the same bound itself.
  double step_phi = 0;
  for (std::size_t k = 0; k < nA; ++k) {
    const std::size_t q = active[k];
    step_phi = std::max(step_phi, eq3_.force_scale(pinned_.junction(q)) * threshold(q) * std::abs(g[k] - z[k]));
  }
  const double damp = step_phi > 0.1 ? 0.1 / step_phi : 1.0;
  if (damp < 1.0) {
    aa.clear();
    return damp;
  }
  if (!aa.step(z, g)) return damp;  // g becomes the accelerated iterate when true
  double jump = 0;
  for (std::size_t k = 0; k < nA; ++k) {
    const std::size_t q = active[k];
    jump = std::max(jump, eq3_.force_scale(pinned_.junction(q)) * threshold(q) * std::abs(g[k] - z[k]));
  }
  if (!(jump <= 0.1)) {  // an extrapolation too far: back to the plain step
    aa.clear();
    for (std::size_t k = 0; k < nA; ++k) {
      const std::size_t q = active[k];
      g[k] = (X * pinned_.a0(q) + pinned_.b0(q) - y1[q]) / threshold(q);
      g[nA + k] = (pinned_.a0(q) - y2[q]) / a_scale;
    }
  }
  return damp;
}

template <PinnedOperator Op>
void ChordSolver<Op>::add_totals(ForceNode& node) const {
  // Totals and their X-derivatives.
  const std::size_t n = pinned_.size();
  double F = F_slip_, dF = 0, A = A_fixed_, dA = 0;
  for (std::size_t q = 0; q < n; ++q) {
    F += node.f[q];
    dF += node.a[q];
    if (pinned_.nonlinear(q)) {
      const std::size_t i = pinned_.junction(q);
      const double phi = eq3_.force_scale(i) * node.f[q];
      A += sheared_area_phi(J_.A0[i], phi);
      dA += sheared_area_phi_slope(J_.A0[i], phi) * eq3_.force_scale(i) * node.a[q];
    }
  }
  node.F = F;
  node.dF = dF;
  node.A = A;
  node.dA = dA;
}

}  // namespace asperity
