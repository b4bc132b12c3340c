#include "solve/interacting/interacting_junctions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/interface_law.hpp"
#include "solve/core/run_limits.hpp"
#include "solve/interacting/solver_failure.hpp"

namespace asperity {

InteractingJunctions::InteractingJunctions(const Problem& problem, std::size_t single_from)
    : law_(problem.law),
      area_law_(problem.law.alpha_b > 0 ? problem.area_law : AreaLaw::until_first_slip),
      nonlinear_law_(problem.law.alpha_b > 0),
      N_(problem.size()),
      J_(problem.A0, problem.law),
      solver_(problem, J_, nonlinear_law_, single_from) {
  n_intact_ = static_cast<std::int64_t>(N_);
  after_change(0.0);
}

InteractingJunctions::Work InteractingJunctions::work() const {
  const PinnedCompliance& G = pinned();
  Work w{solver_.solves(), solver_.iterations(), G.rank_one_updates(), G.rebuilds(),
         overloaded_,      G.single_passes(),    G.single_refreshes()};
  const PinnedCompliance::Timing t = G.timing();
  w.pass_s = t.exact_s + t.single_s + t.deferred_s;
  w.fold_s = t.fold_s;
  w.rebuild_s = t.rebuild_s;
  w.remove_s = t.remove_s;
  w.law_s = solver_.law_seconds();
  w.update_s = solver_.update_seconds();
  return w;
}

bool InteractingJunctions::has_threshold() const { return std::isfinite(x_up_); }
bool InteractingJunctions::has_threshold_below() const { return std::isfinite(x_down_); }

double InteractingJunctions::force(double X) {
  ++force_evals_;
  if (pinned().n_nonlinear() == 0) return X * sum_a0_ + sum_b0_ + solver_.slipping_force();
  return solver_.value(X, &ForceNode::F, &ForceNode::dF, x_up_, x_down_);
}

double InteractingJunctions::area(double X) {
  if (pinned().n_nonlinear() == 0) return solver_.frozen_area();
  return solver_.value(X, &ForceNode::A, &ForceNode::dA, x_up_, x_down_);
}

std::vector<double> InteractingJunctions::forces(double X) {
  std::vector<double> f(J_.force);
  const ForceNode n = solve(X);
  for (std::size_t q = 0; q < pinned().size(); ++q) f[pinned().junction(q)] = n.f[q];
  return f;
}

std::vector<double> InteractingJunctions::areas(const std::vector<double>& f) const {
  std::vector<double> A(N_);
  for (std::size_t i = 0; i < N_; ++i) {
    const bool follows = pinned().position(i) != npos && pinned().nonlinear(pinned().position(i));
    A[i] = follows ? law_.area(J_.A0[i], f[i]) : J_.area[i];
  }
  return A;
}

std::vector<double> InteractingJunctions::load_ratios(double X) {
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
  const std::size_t n = pinned().size();
  if (n == 0) return;
  if (pinned().n_nonlinear() == 0) {  // linear: f_q = X a0_q + b0_q exactly
    for (std::size_t q = 0; q < n; ++q) {
      const double xq = (threshold(q) - pinned().b0(q)) / pinned().a0(q);
      if (pinned().a0(q) > 0 && xq < x_up_) x_up_ = xq, k_up_ = pinned().junction(q);
      if (pinned().a0(q) < 0 && xq > x_down_) x_down_ = xq, k_down_ = pinned().junction(q);
    }
    return;
  }
  for (int dir : {1, -1}) {
    const ForceNode& base = solver_.at(X);
    // Right after a slip the new set's curvatures d²f/dX² at X are known (predicted from the old
    // set's cubic, ChordSolver::slip): Newton's first solve then starts far closer to the slip
    // position than at first order (fewer exact solves: docs/performance.md, "Figures behind the
    // code's choices").
    const std::vector<double>* c = dir > 0 ? solver_.curvatures_at(X) : nullptr;
    // The earliest crossing by that prediction from X.
    std::size_t k = npos;
    double best = HUGE_VAL;
    for (std::size_t q = 0; q < n; ++q) {
      const double a = base.a[q];
      if (dir * a <= 0) continue;
      const double r = threshold(q) - base.f[q];
      double d = r / a;  // signed distance in X
      // The root of r = a d + c d²/2 nearest X (none when it bends away first: first order).
      const double disc = c && r > 0 ? a * a + 2 * (*c)[q] * r : -1.0;
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
      k_down_ = pinned().junction(k);
      continue;
    }
    const double Xt = refine_crossing(X, dir, best, k);
    if (dir > 0)
      x_up_ = Xt, k_up_ = pinned().junction(k);
    else
      x_down_ = Xt, k_down_ = pinned().junction(k);
  }
}

double InteractingJunctions::refine_crossing(double X, int dir, double best, std::size_t& k) {
  const std::size_t n = pinned().size();
  double lo = X, hi = dir * HUGE_VAL;  // bracket: below threshold at lo, over at hi
  double Xt = X + dir * best;
  for (int round = 0;; ++round) {
    if (round > 50) interacting_solver_failure("no slip position found", X);
    // Newton in X on f_k(X) = threshold, kept inside the bracket.
    for (int it = 0;; ++it) {
      if (it > 100) interacting_solver_failure("Newton on a slip position did not converge", Xt);
      const ForceNode& m = solver_.at(Xt);
      const std::size_t qk = k;  // positions do not move while no junction changes state
      const double thr = threshold(qk);
      const double r = m.f[qk] - thr;
      if (r < 0)
        lo = Xt;
      else
        hi = Xt;
      if (std::abs(r) <= solver_.tolerance() * thr) break;
      double next = Xt - r / m.a[qk];
      const bool inside = dir > 0 ? (next > lo && next < hi) : (next < lo && next > hi);
      if (!inside && std::isfinite(hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - Xt) <= 4e-16 * std::abs(Xt)) break;
      Xt = next;
    }
    // Has another junction crossed before? Take the earliest by linear back-extrapolation.
    const ForceNode& m = solver_.at(Xt);
    std::size_t other = npos;
    double earliest = Xt;
    for (std::size_t q = 0; q < n; ++q) {
      const double thr = threshold(q);
      if (q == k || m.f[q] - thr <= 0.1 * solver_.tolerance() * thr) continue;
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
  return Xt;
}

void InteractingJunctions::after_change(double X) {
  // Nodes left in the cache belong to the current set (every change of state clears it).
  sum_a0_ = sum_b0_ = 0;
  for (std::size_t q = 0; q < pinned().size(); ++q) sum_a0_ += pinned().a0(q), sum_b0_ += pinned().b0(q);
  if (pinned().n_nonlinear() > 0) {
    solver_.at(X);
  }
  find_thresholds(X);
  if (pinned().n_nonlinear() > 0) solver_.refine();
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
    if (pinned().size() == 0) {
      after_change(X);
      break;
    }
    // Who is at or over the threshold at this X with the new set? The most overloaded first.
    k = npos;
    if (pinned().n_nonlinear() == 0) {
      double worst = 1.0;
      for (std::size_t q = 0; q < pinned().size(); ++q) {
        const double r = (X * pinned().a0(q) + pinned().b0(q)) / threshold(q);
        if (r >= worst) worst = r, k = pinned().junction(q);
      }
    } else {
      // A junction driven past φ = 1, far over its threshold: the most overloaded slips.
      const ForceNode* solved = nullptr;
      try {
        solved = &solver_.at(X);
      } catch (const OverloadedJunction& o) {
        k = pinned().junction(o.q);
        ++overloaded_;
        continue;
      }
      const ForceNode& m = *solved;
      double worst = 1.0;
      for (std::size_t q = 0; q < pinned().size(); ++q) {
        const double r = m.f[q] / threshold(q);
        if (r >= worst) worst = r, k = pinned().junction(q);
      }
    }
    if (k != npos) {
      if (n > 0 && solver_.past_deadline()) throw WallTimeReached();
      continue;
    }
    after_change(X);
    // A slip position at X itself (rounding): that junction slips now.
    if (x_up_ <= X)
      k = k_up_;
    else if (x_down_ >= X)
      k = k_down_;
    if (k == npos) break;
  }
  return n;
}

void InteractingJunctions::start_slip(std::size_t i, double X) {
  const std::size_t q = pinned().position(i);
  const bool always = area_law_ == AreaLaw::always;
  double f_sl;
  if (pinned().nonlinear(q)) {
    if (always) {
      f_sl = law_.slipping_force_always(J_.A0[i]);
      J_.set_contact(i, contact_at_force(law_, J_.A0[i], f_sl));
    } else {
      J_.set_contact(i, contact_at_first_slip(law_, J_.A0[i]));
      f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
    }
  } else {
    f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
  }
  if (J_.intact[i]) J_.intact[i] = 0, --n_intact_;
  J_.pinned[i] = 0;
  J_.force[i] = f_sl;
  // Its frozen area counts in the totals from now on when it followed its force.
  solver_.slip(q, f_sl, J_.area[i], X);
}

void InteractingJunctions::repin_all(double X) {
  if (pinned().size() == N_) return;
  ++repins_;
  // Converged forces (1e-12 of the slip forces, whatever the knob): the anchors set here carry
  // the forces' error into every later state, and a repin is rare.
  std::vector<double> f(J_.force);
  const ForceNode now = solver_.solve(X, std::min(solver_.tolerance(), 1e-12));
  for (std::size_t q = 0; q < pinned().size(); ++q) f[pinned().junction(q)] = now.f[q];
  const bool always = area_law_ == AreaLaw::always;
  for (std::size_t j = 0; j < N_; ++j) {
    if (pinned().position(j) != npos) continue;
    // x_j = X − u_j(f_j) − Σ_l C_jl f_l: the equation holds with the forces of now.
    double uc = 0;
    for (std::size_t l = 0; l < N_; ++l) uc += pinned().coupling(j, l) * f[l];
    const double u = solver_.repin(j, always && nonlinear_law_, f[j], J_.area[j]);
    J_.anchor[j] = X - u - uc;
    J_.pinned[j] = 1;
  }
  solver_.repinned(J_.anchor);
  // Rounding of the new G may put a junction that was at its threshold a hair over it.
  settle(X, npos);
}

}  // namespace asperity
