#include "solve/interacting/interacting_junctions.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/interface_law.hpp"
#include "solve/core/run_limits.hpp"
#include "solve/interacting/anderson.hpp"
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
  Work w{solves_,
         iterations_,
         pinned_.rank_one_updates(),
         pinned_.rebuilds(),
         overloaded_,
         pinned_.single_passes(),
         pinned_.single_refreshes()};
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

void InteractingJunctions::own(std::size_t q, double f, double& u, double& du) {
  const std::size_t i = pinned_.junction(q);
  if (pinned_.nonlinear(q)) return eq3_.at(i, f, u, du);
  u = f / J_.k[i];
  du = 1.0 / J_.k[i];
}

double InteractingJunctions::force(double X) {
  ++force_evals_;
  if (pinned_.n_nonlinear() == 0) return X * sum_a0_ + sum_b0_ + F_slip_;
  return cache_.value(X, &ForceNode::F, &ForceNode::dF, x_up_, x_down_);
}

double InteractingJunctions::area(double X) {
  if (pinned_.n_nonlinear() == 0) return A_fixed_;
  return cache_.value(X, &ForceNode::A, &ForceNode::dA, x_up_, x_down_);
}

std::vector<double> InteractingJunctions::forces(double X) {
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
    const double Xt = refine_crossing(X, dir, best, k);
    if (dir > 0)
      x_up_ = Xt, k_up_ = pinned_.junction(k);
    else
      x_down_ = Xt, k_down_ = pinned_.junction(k);
  }
}

double InteractingJunctions::refine_crossing(double X, int dir, double best, std::size_t& k) {
  const std::size_t n = pinned_.size();
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
      if (r < 0)
        lo = Xt;
      else
        hi = Xt;
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
  return Xt;
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
    if (x_up_ <= X)
      k = k_up_;
    else if (x_down_ >= X)
      k = k_down_;
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
