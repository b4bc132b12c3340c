#include "solve/interacting/interacting_junctions.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/interface_law.hpp"
#include "solve/interacting/anderson.hpp"
#include "solve/core/run_limits.hpp"
#include "solve/interacting/solver_failure.hpp"

namespace asperity {

namespace {

// u'(0) = 1/k0 for both kinds of junction: the first reference compliances.
std::vector<double> initial_reference(const JunctionState& J) {
  std::vector<double> D(J.k.size());
  for (std::size_t i = 0; i < D.size(); ++i) D[i] = 1.0 / J.k[i];
  return D;
}

}  // namespace

InteractingJunctions::InteractingJunctions(const Problem& problem, std::size_t single_from)
    : p_(problem),
      law_(problem.law),
      area_law_(problem.law.alpha_b > 0 ? problem.area_law : AreaLaw::until_first_slip),
      nonlinear_law_(problem.law.alpha_b > 0),
      tol_(problem.solver.interaction_tolerance),
      N_(problem.size()),
      J_(problem.A0, problem.law),
      eq3_(nonlinear_law_ ? Eq3Displacement(problem.law, J_.A0) : Eq3Displacement()),
      pinned_(problem, initial_reference(J_), nonlinear_law_, single_from),
      cache_([this](double X) { return solve(X); }, 0.1 * problem.solver.tolerance),
      teams_(omp_get_max_threads()) {
  if (!nonlinear_law_)
    for (std::size_t i = 0; i < N_; ++i) A_fixed_ += J_.A0[i];
  n_intact_ = static_cast<std::int64_t>(N_);
  last_f_.assign(N_, 0.0);
  last_a_.assign(N_, 0.0);
  // The first event search (solves, rebuilds: over eight minutes at N = 20,000) counts.
  deadline_ = wall_deadline(problem.limits);
  after_change(0.0);
}

InteractingJunctions::Work InteractingJunctions::work() const {
  Work w{solves_,          iterations_, pinned_.rank_one_updates(), pinned_.rebuilds(), overloaded_,
         pinned_.single_passes(), pinned_.single_refreshes()};
  const PinnedCompliance::Timing t = pinned_.timing();
  w.pass_s = t.exact_s + t.single_s + t.deferred_s;
  w.fold_s = t.fold_s;
  w.rebuild_s = t.rebuild_s;
  w.remove_s = t.remove_s;
  w.law_s = teams_.laws.seconds();
  w.update_s = teams_.updates.seconds();
  return w;
}

bool InteractingJunctions::has_threshold() const { return std::isfinite(x_up_); }
bool InteractingJunctions::has_threshold_below() const { return std::isfinite(x_down_); }

double InteractingJunctions::threshold(std::size_t q) const {
  const std::size_t i = pinned_.junction(q);
  // Eq. (3) junctions slip at f = σ A(f), φ = φ_s; the others at σ times their frozen area.
  return pinned_.nonlinear(q) ? eq3_.slip_force(i) : J_.f_s[i];
}

void InteractingJunctions::own(std::size_t q, double f, double& u, double& du) const {
  const std::size_t i = pinned_.junction(q);
  if (pinned_.nonlinear(q)) return eq3_.at(i, f, u, du);
  u = f / J_.k[i];
  du = 1.0 / J_.k[i];
}

// ---- exact solves -------------------------------------------------------------------------

void InteractingJunctions::warm_start(double X, std::vector<double>& f, std::vector<double>& a) const {
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
    auto it = std::lower_bound(cache_.nodes().begin(), cache_.nodes().end(), X, [](const ForceNode& k, double x) { return k.X < x; });
    std::size_t hi = static_cast<std::size_t>(it - cache_.nodes().begin());
    hi = std::clamp<std::size_t>(hi, 1, m - 1);
    const ForceNode& n0 = cache_.nodes()[hi - 1];
    const ForceNode& n1 = cache_.nodes()[hi];
    const double h = n1.X - n0.X;
    const double t = (X - n0.X) / h;
    if (h > 0 && t >= -2.0 && t <= 3.0) {
      for (std::size_t q = 0; q < n; ++q)
        f[q] = hermite(n0.X, n1.X, n0.f[q], n0.a[q], n1.f[q], n1.a[q], X, &a[q]);
      return;
    }
  }
  if (m >= 1) {
    const ForceNode* near = &cache_.nodes()[0];
    for (const ForceNode& k : cache_.nodes())
      if (std::abs(k.X - X) < std::abs(near->X - X)) near = &k;
    // From the node a slip left, with the curvatures predicted there: second order.
    // (Within twice the old nodes' spacing, where that cubic's curvature holds.)
    const bool curved = seed_valid_ && near->X == seed_X_ && seed_c_.size() == n && std::abs(X - near->X) <= 2 * seed_h_;
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

ForceNode InteractingJunctions::solve(double X, double tol) const {
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
    std::vector<double> dl(n, 0.0), da(n, 0.0), y1(n), y2(n);
    std::vector<std::size_t> active;
    active.reserve(pinned_.n_nonlinear());
    for (std::size_t q = 0; q < n; ++q)
      if (pinned_.nonlinear(q)) active.push_back(q);
    // Anderson acceleration of the chord map on the active positions' forces and slopes, scaled
    // to O(1) (f by the slip force, df/dX by the mean |a0|). The chord map contracts linearly at
    // the drift of u' from D, almost the same linear map from one iteration to the next, so the
    // last few residuals predict most of the remaining error: fewer passes over G for the same
    // fixed point (the stopping rule is unchanged).
    const std::size_t nA = active.size();
    double a_scale = 0;
    for (std::size_t q : active) a_scale += std::abs(pinned_.a0(q));
    a_scale = nA > 0 && a_scale > 0 ? a_scale / static_cast<double>(nA) : 1.0;
    Anderson aa(2 * nA);
    std::vector<double> z(2 * nA), g(2 * nA);
    // A pass may read G's single-precision copy where its error stays within a tenth of the
    // tolerance of each slip force (the fixed point then moves by at most that over 1 − ρ; the
    // stopping rule is unchanged) and within ten times the tolerance of the slopes' mean scale
    // (the slopes only shape the interpolants and Newton's rate: at N = 2,400, 711 more passes on
    // the copy than with the tolerance itself, of 17,363, and the peak equal to 1e-15; a tenth
    // held the copy back every other pass).
    const bool single = pinned_.single_kept();
    PinnedCompliance::PassBudget budget;
    if (single) {
      budget.y1.resize(n);
      for (std::size_t q = 0; q < n; ++q) budget.y1[q] = 0.1 * tol * threshold(q);
      budget.y2 = 10 * tol * a_scale;
    }
    double previous = HUGE_VAL;
    int iter = 0, refreshes = 0;
    for (;;) {
      ++iter;
      // The run's wall-time limit, read at every pass: at N = 20,000 one step's solves and their
      // Newton refreshes (rebuilds of about 90 s) took over ten minutes past it.
      if (std::chrono::steady_clock::now() >= deadline_) throw WallTimeReached();
      // The junctions' own laws, each independent of the others (the same numbers on any
      // number of threads): a tenth of a pass's time, worth splitting from a few hundred on.
      {
      const AdaptiveTeam::Region region(teams_.laws, static_cast<double>(nA));
      const int threads = region.threads();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        double u, du;
        own(q, node.f[q], u, du);
        dl[q] = u - pinned_.reference(q) * node.f[q];
        da[q] = (du - pinned_.reference(q)) * node.a[q];
      }
      }
      // y = G [Δ, Δ'a]: one pass over the rows of the nonlinear positions.
      if (single)
        pinned_.apply(active, dl, da, y1, y2, budget);
      else
        pinned_.apply(active, dl, da, y1, y2);
      // The chord map's image g and the current iterate z, scaled, on the active positions.
      // This loop and the update below are per junction (and a maximum), the same numbers on
      // any number of threads; split like the laws above (on two threads the other thread
      // otherwise waits through them).
      {
      const AdaptiveTeam::Region region(teams_.updates, static_cast<double>(nA));
      const int threads = region.threads();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        const double thr = threshold(q);
        z[k] = node.f[q] / thr;
        g[k] = (X * pinned_.a0(q) + pinned_.b0(q) - y1[q]) / thr;
        z[nA + k] = node.a[q] / a_scale;
        g[nA + k] = (pinned_.a0(q) - y2[q]) / a_scale;
      }
      }
      const double damp = chord_step(X, active, a_scale, y1, y2, z, g, aa);
      double change = 0;
      for (std::size_t q = 0; q < n; ++q) {
        if (pinned_.nonlinear(q)) continue;
        const double f = node.f[q] + damp * (X * pinned_.a0(q) + pinned_.b0(q) - y1[q] - node.f[q]);
        change = std::max(change, std::abs(f - node.f[q]) / threshold(q));
        node.f[q] = f;
        node.a[q] = pinned_.a0(q) - y2[q];
      }
      {
      const AdaptiveTeam::Region region(teams_.updates, static_cast<double>(nA));
      const int threads = region.threads();
#pragma omp parallel for schedule(static) reduction(max : change) num_threads(threads) if (threads > 1)
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        const double thr = threshold(q);
        const double f = thr * (z[k] + damp * (g[k] - z[k]));
        change = std::max(change, std::abs(f - node.f[q]) / thr);
        node.f[q] = f;
        node.a[q] = a_scale * g[nA + k];
      }
      }
      // Long after a solve normally ends (2-9 passes, about 20 with refreshes), an iterate past
      // φ = 1, or over a threshold while still far from any fixed point (1e-2 of the slip forces,
      // or 100 times the tolerance if less): a junction far over its threshold, which the
      // iteration cannot follow (see Overloaded; the stand-in P6.40N at α_b = 2.06e-16, ε =
      // 0.503, η = 300 cycled between φ = 0.89 and 0.99 of a junction whose threshold is 0.63).
      if (iter >= 30) overloaded_check(X, active, node.f, change, std::min(100 * tol, 1e-2));
      // Converged to solver.interaction_tolerance of the slip force. The solves' errors reach the
      // observables damped (measured: the default 1e-8 moves Q_s, A_s and t_peak by ≤ 1e-9
      // relative against 1e-12, for 0.6 of the passes; docs/interactions.md, "The interaction
      // tolerance").
      if (change <= tol) break;
      // Contracting by ρ, the iterate is about ρ/(1 − ρ) times the last change from the fixed
      // point: stop when that is already within the tolerance (one pass fewer; never above ten
      // times it off).
      if (iter >= 3 && change <= 10 * tol && change < 0.5 * previous) {
        const double rho = change / previous;
        if (change * rho / (1.0 - rho) <= tol) break;
      }
      // Stalled at rounding: the change stops shrinking once it is of the order of the rounding
      // of the sums (about 1e-11 of the slip force; at a looser tolerance the solve has stopped
      // before, so this never ends one early).
      if (iter >= 3 && change < std::min(10 * tol, 1e-11) && change > 0.5 * previous) break;
      // Slow contraction: the reference compliances drifted from the junctions' own. Take them
      // at the current forces and rebuild G (a Newton step's Jacobian): the solution is the
      // same, the iteration fast again.
      // A rebuild costs about n/8 passes over G (O(n³) against O(n²), measured at n = 1,200),
      // so the slow passes are paid until they add up to one (a rent-or-buy rule: at most twice
      // the better of the two), unless this solve stalls or grows.
      // Slow: contracting by more than 0.2 a pass, or by more than 0.5 within ten times the
      // tolerance (where the estimate above cannot stop it yet).
      const bool slow = iter >= 3 && ((change > 0.2 * previous && change > 10 * tol) || (change > 0.5 * previous && change > tol));
      if (pinned_.rebuilds() != slow_since_) slow_since_ = pinned_.rebuilds(), slow_passes_ = 0;
      if (slow) ++slow_passes_;
      const bool worth = slow_passes_ * 8 >= static_cast<std::int64_t>(n) || change > previous || iter >= 20;
      if (slow && worth && refreshes < 5) {
        ++refreshes;
        for (std::size_t q : active) {
          double u, du;
          own(q, node.f[q], u, du);
          pinned_.set_reference(q, du);
        }
        pinned_.rebuild();
        aa.clear();
        previous = HUGE_VAL;
        continue;
      }
      if (iter >= 200) interacting_solver_failure("the chord iteration did not converge in 200 iterations", X);
      previous = change;
    }
    iterations_ += iter;
  }
  add_totals(node);
  for (std::size_t q = 0; q < n; ++q) {
    last_f_[pinned_.junction(q)] = node.f[q];
    last_a_[pinned_.junction(q)] = node.a[q];
  }
  ++solves_;
  return node;
}

void InteractingJunctions::overloaded_check(double X, const std::vector<std::size_t>& active,
                                            const std::vector<double>& f, double change, double stuck) const {
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
  throw Overloaded(what, worst);
}

double InteractingJunctions::chord_step(double X, const std::vector<std::size_t>& active, double a_scale,
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

void InteractingJunctions::add_totals(ForceNode& node) const {
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

double InteractingJunctions::force(double X) const {
  ++force_evals_;
  if (pinned_.n_nonlinear() == 0) return X * sum_a0_ + sum_b0_ + F_slip_;
  return cache_.value(X, &ForceNode::F, &ForceNode::dF, x_up_, x_down_);
}

double InteractingJunctions::area(double X) const {
  if (pinned_.n_nonlinear() == 0) return A_fixed_;
  return cache_.value(X, &ForceNode::A, &ForceNode::dA, x_up_, x_down_);
}

std::vector<double> InteractingJunctions::forces(double X) const {
  std::vector<double> f(J_.force);
  const ForceNode n = solve(X);
  for (std::size_t q = 0; q < pinned_.size(); ++q) f[pinned_.junction(q)] = n.f[q];
  return f;
}

std::vector<double> InteractingJunctions::areas(const std::vector<double>& f) const {
  std::vector<double> A(N_);
  for (std::size_t i = 0; i < N_; ++i) {
    const bool follows = pinned_.position(i) != npos && pinned_.nonlinear(pinned_.position(i));
    A[i] = follows ? law_.area(J_.A0[i], f[i]) : J_.area[i];
  }
  return A;
}

std::vector<double> InteractingJunctions::load_ratios(double X) const {
  const std::vector<double> f = forces(X);
  const std::vector<double> A = areas(f);
  std::vector<double> r(N_);
  for (std::size_t i = 0; i < N_; ++i) r[i] = f[i] / (law_.sigma * A[i]);
  return r;
}

// ---- events -------------------------------------------------------------------------------

void InteractingJunctions::find_thresholds(double X) {
  x_up_ = HUGE_VAL;
  x_down_ = -HUGE_VAL;
  k_up_ = k_down_ = npos;
  const std::size_t n = pinned_.size();
  if (n == 0) return;
  if (pinned_.n_nonlinear() == 0) {  // linear: f_q = X a0_q + b0_q exactly
    for (std::size_t q = 0; q < n; ++q) {
      const double xq = (threshold(q) - pinned_.b0(q)) / pinned_.a0(q);
      if (pinned_.a0(q) > 0 && xq < x_up_) x_up_ = xq, k_up_ = pinned_.junction(q);
      if (pinned_.a0(q) < 0 && xq > x_down_) x_down_ = xq, k_down_ = pinned_.junction(q);
    }
    return;
  }
  for (int dir : {1, -1}) {
    const ForceNode& base = cache_.at(X);
    // Right after a slip the new set's curvatures d²f/dX² at X are known (predicted from the old
    // set's cubic, remove_pinned). The first-order prediction put Newton's first solve within the
    // tolerance in 8 % (N = 1,200) and 14 % (2,400) of the slips; extrapolated from those solves,
    // the second-order one would in 79 % and 90 %. Measured: exact solves −22 % at both sizes.
    const bool curved = dir > 0 && seed_valid_ && seed_X_ == X && seed_c_.size() == n;
    // The earliest crossing by that prediction from X.
    std::size_t k = npos;
    double best = HUGE_VAL;
    for (std::size_t q = 0; q < n; ++q) {
      const double a = base.a[q];
      if (dir * a <= 0) continue;
      const double r = threshold(q) - base.f[q];
      double d = r / a;  // signed distance in X
      // The root of r = a d + c d²/2 nearest X (none when it bends away first: first order).
      const double disc = curved && r > 0 ? a * a + 2 * seed_c_[q] * r : -1.0;
      if (disc > 0) d = 2 * r / (a + std::sqrt(disc));
      if (dir * d >= 0 && std::abs(d) < best) best = std::abs(d), k = q;
    }
    if (k == npos) continue;
    if (dir < 0) {
      // A junction whose force grows as X decreases (shielded by its neighbours) is rare and its
      // crossing usually far behind: the first-order prediction is the event, and reaching it
      // slips the junction only if it is over its threshold there (slip_crossed re-checks and
      // predicts again), so no solve is spent deep behind X where the slider never goes.
      x_down_ = X - best;
      k_down_ = pinned_.junction(k);
      continue;
    }
    double lo = X, hi = dir * HUGE_VAL;  // bracket: below threshold at lo, over at hi
    double Xt = X + dir * best;
    for (int round = 0;; ++round) {
      if (round > 50) interacting_solver_failure("no slip position found", X);
      // Newton in X on f_k(X) = threshold, kept inside the bracket.
      for (int it = 0;; ++it) {
        if (it > 100) interacting_solver_failure("Newton on a slip position did not converge", Xt);
        const ForceNode& m = cache_.at(Xt);
        const std::size_t qk = k;  // positions do not move while no junction changes state
        const double thr = threshold(qk);
        const double r = m.f[qk] - thr;
        if (r < 0) lo = Xt; else hi = Xt;
        if (std::abs(r) <= tol_ * thr) break;
        double next = Xt - r / m.a[qk];
        const bool inside = dir > 0 ? (next > lo && next < hi) : (next < lo && next > hi);
        if (!inside && std::isfinite(hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - Xt) <= 4e-16 * std::abs(Xt)) break;
        Xt = next;
      }
      // Has another junction crossed before? Take the earliest by linear back-extrapolation.
      const ForceNode& m = cache_.at(Xt);
      std::size_t other = npos;
      double earliest = Xt;
      for (std::size_t q = 0; q < n; ++q) {
        const double thr = threshold(q);
        if (q == k || m.f[q] - thr <= 0.1 * tol_ * thr) continue;
        const double back = m.a[q] != 0 ? Xt - (m.f[q] - thr) / m.a[q] : lo;
        const double xb = dir > 0 ? std::clamp(back, std::min(lo, X), Xt) : std::clamp(back, Xt, std::max(lo, X));
        if (other == npos || dir * xb < dir * earliest) other = q, earliest = xb;
      }
      if (other == npos) break;
      k = other;
      hi = Xt;
      lo = X;
      Xt = earliest;
      if (Xt == X || Xt == hi) Xt = 0.5 * (lo + hi);
    }
    if (dir > 0) x_up_ = Xt, k_up_ = pinned_.junction(k);
    else x_down_ = Xt, k_down_ = pinned_.junction(k);
  }
}

void InteractingJunctions::after_change(double X) {
  // Nodes left in the cache belong to the current set (every change of state clears it).
  sum_a0_ = sum_b0_ = 0;
  for (std::size_t q = 0; q < pinned_.size(); ++q) sum_a0_ += pinned_.a0(q), sum_b0_ += pinned_.b0(q);
  if (pinned_.n_nonlinear() > 0) {
    cache_.at(X);
  }
  find_thresholds(X);
  if (pinned_.n_nonlinear() > 0) cache_.refine();
}

std::int64_t InteractingJunctions::slip_crossed(double X) {
  // The slip position above X is exact (Newton): its junction slips. The one below X is a
  // prediction: whoever is at or over the threshold at X slips (possibly nobody; then the
  // prediction is renewed from X).
  return settle(X, X >= x_up_ ? k_up_ : npos);
}

std::int64_t InteractingJunctions::settle(double X, std::size_t k) {
  std::int64_t n = 0;
  for (;;) {
    if (k != npos) {
      start_slip(k, X);
      ++n;
      ++slips_;  // counted at once: a stop inside the avalanche keeps the count
    }
    if (pinned_.size() == 0) {
      after_change(X);
      break;
    }
    // Who is at or over the threshold at this X with the new set? The most overloaded first.
    k = npos;
    if (pinned_.n_nonlinear() == 0) {
      double worst = 1.0;
      for (std::size_t q = 0; q < pinned_.size(); ++q) {
        const double r = (X * pinned_.a0(q) + pinned_.b0(q)) / threshold(q);
        if (r >= worst) worst = r, k = pinned_.junction(q);
      }
    } else {
      // A junction driven past φ = 1, far over its threshold: the most overloaded slips.
      const ForceNode* solved = nullptr;
      try {
        solved = &cache_.at(X);
      } catch (const Overloaded& o) {
        k = pinned_.junction(o.q);
        ++overloaded_;
        continue;
      }
      const ForceNode& m = *solved;
      double worst = 1.0;
      for (std::size_t q = 0; q < pinned_.size(); ++q) {
        const double r = m.f[q] / threshold(q);
        if (r >= worst) worst = r, k = pinned_.junction(q);
      }
    }
    if (k != npos) {
      if (n > 0 && std::chrono::steady_clock::now() >= deadline_) throw WallTimeReached();
      continue;
    }
    after_change(X);
    // A slip position at X itself (rounding): that junction slips now.
    if (x_up_ <= X) k = k_up_;
    else if (x_down_ >= X) k = k_down_;
    if (k == npos) break;
  }
  return n;
}

void InteractingJunctions::start_slip(std::size_t i, double X) {
  const std::size_t q = pinned_.position(i);
  const bool always = area_law_ == AreaLaw::always;
  double f_sl;
  if (pinned_.nonlinear(q)) {
    if (always) {
      f_sl = law_.slipping_force_always(J_.A0[i]);
      J_.set_contact(i, contact_at_force(law_, J_.A0[i], f_sl));
    } else {
      J_.set_contact(i, contact_at_first_slip(law_, J_.A0[i]));
      f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
    }
    A_fixed_ += J_.area[i];
  } else {
    f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
  }
  if (J_.intact[i]) J_.intact[i] = 0, --n_intact_;
  J_.pinned[i] = 0;
  J_.force[i] = f_sl;
  F_slip_ += f_sl;
  // The old set's solution nearest X (the slip position's node: X is its event, located to the
  // integrator's resolution), from which the new set's seed at X is predicted (below).
  const ForceNode* near = nullptr;
  for (const ForceNode& m : cache_.nodes())
    if (!near || std::abs(m.X - X) < std::abs(near->X - X)) near = &m;
  // The node farthest from it (the last Newton iterates sit within rounding of each other, too
  // close for a second difference): with it, the per-junction curvature at X.
  const ForceNode* other = nullptr;
  for (const ForceNode& m : cache_.nodes())
    if (near && (!other || std::abs(m.X - near->X) > std::abs(other->X - near->X))) other = &m;
  remove_pinned(q, f_sl, near, other, X);
  cache_.clear();
}

void InteractingJunctions::remove_pinned(std::size_t q, double f_sl, const ForceNode* at_X, const ForceNode* other,
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
    // The positions as PinnedCompliance::remove leaves them: the last moves into q.
    if (q != n - 1) seed_f_[q] = seed_f_[n - 1], seed_a_[q] = seed_a_[n - 1];
    seed_f_.pop_back();
    seed_a_.pop_back();
    if (!seed_c_.empty()) {
      if (q != n - 1) seed_c_[q] = seed_c_[n - 1];
      seed_c_.pop_back();
    }
  }
  pinned_.remove(q, f_sl);
}

void InteractingJunctions::repin_all(double X) {
  if (pinned_.size() == N_) return;
  ++repins_;
  // Converged forces (1e-12 of the slip forces, whatever the knob): the anchors set here carry
  // the forces' error into every later state, and a repin is rare.
  std::vector<double> f(J_.force);
  const ForceNode now = solve(X, std::min(tol_, 1e-12));
  for (std::size_t q = 0; q < pinned_.size(); ++q) f[pinned_.junction(q)] = now.f[q];
  const bool always = area_law_ == AreaLaw::always;
  for (std::size_t j = 0; j < N_; ++j) {
    if (pinned_.position(j) != npos) continue;
    // x_j = X − u_j(f_j) − Σ_l C_jl f_l: the equation holds with the forces of now.
    double uc = 0;
    for (std::size_t l = 0; l < N_; ++l) uc += pinned_.coupling(j, l) * f[l];
    const std::size_t q = pinned_.add(j, always && nonlinear_law_);
    double u, du;
    own(q, f[j], u, du);
    pinned_.set_reference(q, du);
    J_.anchor[j] = X - u - uc;
    J_.pinned[j] = 1;
    if (pinned_.nonlinear(q)) A_fixed_ -= J_.area[j];
  }
  pinned_.set_anchors(J_.anchor);  // nobody slips: h = x
  F_slip_ = 0.0;
  cache_.clear();  // its nodes belong to the old set
  seed_valid_ = false;
  seed_c_.clear();
  pinned_.rebuild();
  // Rounding of the new G may put a junction that was at its threshold a hair over it.
  settle(X, npos);
}

}  // namespace asperity
