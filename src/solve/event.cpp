// Event-driven solver (`solver.method: event`). Solves the same continuous model as the
// reference (its dt → 0 limit) with an adaptive Dormand–Prince 5(4) integrator (Boost.Odeint,
// dense output) between events, and locates every event in time on the dense output
// (Boost.Math TOMS 748): a junction reaching its slip threshold, the slider slowing below
// c_min·v (repinning), and the slider velocity crossing v (extrema of Q). Between events the
// state is smooth, so steps are long during slow loading and short only where needed.
//
// Structure used (MODEL.md §4): slip thresholds are positions in X, kept in one min-heap;
// linear pinned junctions enter the force through two aggregate sums (Σk, Σk·x), slipping
// ones through one (Σε f_s); only never-slipped junctions (or, with area_law: always, every
// pinned one) need their own nonlinear force, given by the universal law instead of a
// bisection. All controlled by solver.tolerance; the universal-law table is kept ~1e-13 exact.
#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <vector>

#include "physics/universal_law.hpp"
#include "solve/binned_sum.hpp"
#include "solve/integrate.hpp"

namespace asperity {
namespace {

namespace odeint = boost::numeric::odeint;
using State = std::array<double, 2>;  // (X / L, V / v): scaled so one tolerance fits both

enum class Phase : std::uint8_t { pinned, slipping };

class EventModel {
 public:
  EventModel(const Scene& scene)
      : e_(scene.experiment),
        m_(scene.model),
        law_(make_contact_law(e_, m_)),
        always_(m_.area_law == AreaLaw::always),
        nonlinear_(m_.alpha_b > 0) {
    const std::size_t N = e_.junctions.size();
    A0_ = e_.junctions.area_m2;
    w_.resize(N); c_.resize(N); d_s_.resize(N); k_.resize(N); f_s_.resize(N); A_.resize(N);
    x_.assign(N, 0.0); f_sl_.assign(N, 0.0); A_sl_.assign(N, 0.0); k_sl_.assign(N, 0.0);
    phase_.assign(N, Phase::pinned);
    intact_.assign(N, 1);
    nl_pos_.assign(N, npos);
    double psi_hi = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const double A0 = A0_[i];
      w_[i] = initial_diameter(A0) * law_.E;
      k_[i] = law_.stiffness(A0, A0);
      A_[i] = A0;
      f_s_[i] = law_.sigma * A0;
      if (nonlinear_) {
        c_[i] = w_[i] * law_.force_scale(A0);
        const double phi_s = law_.slip_phi(A0);
        const double psi_s = phi_s / stiffness_factor(1.0 - phi_s * phi_s, law_.nu, law_.shape);
        d_s_[i] = psi_s / c_[i];
        psi_hi = std::max(psi_hi, psi_s);
        if (always_) {
          f_sl_[i] = law_.slipping_force_always(A0);
          A_sl_[i] = law_.area(A0, f_sl_[i]);
          k_sl_[i] = law_.stiffness(A0, A_sl_[i]);
        }
      } else {
        d_s_[i] = f_s_[i] / k_[i];  // linear junction: f = k0 X reaches σ A0
      }
    }
    if (nonlinear_) {
      // At least ψ ≤ 1e-3: a table over a tiny range (slip thresholds of ψ < 1e-6, e.g.
      // sigma_exp = 1e-2 Pa) comes out of the spline fit wrong by orders of magnitude (force
      // 1e10 times too stiff: the run crawled at 1e-9 s steps), while g is as smooth on [0, 1e-3].
      // Shipped scenes have ψ_s ~ 1, so their table is unchanged.
      table_.emplace(law_.nu, law_.shape, std::max(1.1 * psi_hi, 1e-3));
      if (!(table_->max_rel_error() <= 1e-11)) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      "event solver: the universal force law's table is only accurate to %.3g (psi up to %.3g): "
                      "junctions outside the contact law's range",
                      table_->max_rel_error(), 1.1 * psi_hi);
        throw SolverError(msg);
      }
      if (!always_ && N >= kBinnedMin) {
        binned_.emplace(*table_, w_, c_, A0_, binned_rel_width(scene.solver.tolerance, psi_hi));
        std::fill(nl_pos_.begin(), nl_pos_.end(), 0);  // "in the nonlinear set"; storage is binned_
      } else {
        for (std::size_t i = 0; i < N; ++i) nl_insert(i, 0.0);
      }
    } else {
      for (std::size_t i = 0; i < N; ++i) lin_insert(i, 0.0);
      for (double a : A0_) A_fixed_ += a;  // linear junctions keep their area
    }
    for (std::size_t i = 0; i < N; ++i) heap_.push({d_s_[i], static_cast<std::uint32_t>(i)});
    n_intact_ = static_cast<std::int64_t>(N);
  }

  // Total junction force at slider position X [N].
  double force(double X) const {
    ++force_evals_;
    double F = K_p_ * X - S_p_ + F_sl_;
    if (binned_) return F + binned_->force(X);
    const std::size_t n = nl_w_.size();
    const double* w = nl_w_.data();
    const double* c = nl_c_.data();
    const double* x = nl_x_.data();
    if (n == 0) return F;
    const UniversalForceLaw& g = *table_;
    double Fnl = 0;
#pragma omp parallel for reduction(+ : Fnl) schedule(static) if (n > 65536)
    for (std::size_t j = 0; j < n; ++j) {
      const double d = X - x[j];
      Fnl += w[j] * d * g.g(c[j] * d);
    }
    return F + Fnl;
  }

  // Total area at slider position X [m²].
  double area(double X) const {
    double A = A_fixed_;
    if (binned_) return A + binned_->area(X);
    for (std::size_t j = 0; j < nl_w_.size(); ++j) {
      const double d = X - nl_x_[j];
      const double psi = nl_c_[j] * d;
      const double phi = psi * table_->g(psi);
      A += nl_A0_[j] * (1.0 - phi * phi);
    }
    return A;
  }

  bool has_threshold() const { return !heap_.empty(); }
  double next_threshold() const { return heap_.top().first; }
  std::int64_t n_slipping() const { return static_cast<std::int64_t>(slipping_.size()); }
  std::int64_t n_intact() const { return n_intact_; }
  std::int64_t force_evals() const { return force_evals_; }
  std::int64_t slips() const { return slips_; }
  std::int64_t repins() const { return repins_; }

  // Every pinned junction whose threshold X has reached slips; returns how many.
  std::int64_t slip_crossed(double X) {
    std::int64_t n = 0;
    while (!heap_.empty() && heap_.top().first <= X) {
      const std::uint32_t i = heap_.top().second;
      heap_.pop();
      start_slip(i);
      ++n;
    }
    slips_ += n;
    return n;
  }

  // All slipping junctions repin at X, with no force jump.
  void repin_all(double X) {
    if (slipping_.empty()) return;
    ++repins_;
    for (std::uint32_t i : slipping_) {
      phase_[i] = Phase::pinned;
      if (always_ && nonlinear_) {
        A_fixed_ -= A_sl_[i];
        nl_insert(i, X - f_sl_[i] / k_sl_[i]);
        heap_.push({nl_x_[nl_pos_[i]] + d_s_[i], i});
      } else {
        lin_insert(i, X - law_.epsilon * f_s_[i] / k_[i]);
        heap_.push({x_[i] + f_s_[i] / k_[i], i});
      }
    }
    slipping_.clear();
    F_sl_ = 0.0;  // exactly: no slipping junction is left
    maybe_resum();
  }

 private:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  // Above this many junctions the never-slipped ones are summed in bins (binned_sum.hpp):
  // O(bins) per force instead of O(N). Below it the exact sum is as fast, and exact.
  static constexpr std::size_t kBinnedMin = 20000;

  void nl_insert(std::size_t i, double anchor) {
    nl_pos_[i] = nl_w_.size();
    nl_idx_.push_back(static_cast<std::uint32_t>(i));
    nl_w_.push_back(w_[i]);
    nl_c_.push_back(c_[i]);
    nl_x_.push_back(anchor);
    nl_A0_.push_back(A0_[i]);
  }
  void nl_remove(std::size_t i) {
    if (binned_) {
      binned_->remove(i);
      nl_pos_[i] = npos;
      return;
    }
    const std::size_t p = nl_pos_[i], last = nl_w_.size() - 1;
    if (p != last) {
      const std::uint32_t moved = nl_idx_[last];
      nl_idx_[p] = moved; nl_w_[p] = nl_w_[last]; nl_c_[p] = nl_c_[last];
      nl_x_[p] = nl_x_[last]; nl_A0_[p] = nl_A0_[last];
      nl_pos_[moved] = p;
    }
    nl_idx_.pop_back(); nl_w_.pop_back(); nl_c_.pop_back(); nl_x_.pop_back(); nl_A0_.pop_back();
    nl_pos_[i] = npos;
  }
  void lin_insert(std::size_t i, double anchor) {
    x_[i] = anchor;
    K_p_ += k_[i];
    S_p_ += k_[i] * anchor;
    ++updates_;
  }

  void start_slip(std::uint32_t i) {
    if (nl_pos_[i] != npos) {
      nl_remove(i);
      if (always_) {
        A_fixed_ += A_sl_[i];
      } else {
        // First slip of a never-slipped junction: A, k and f_s freeze at the exact slip point.
        const double phi_s = law_.slip_phi(A0_[i]);
        A_[i] = A0_[i] * (1.0 - phi_s * phi_s);
        k_[i] = w_[i] * stiffness_factor(A_[i] / A0_[i], law_.nu, law_.shape);
        f_s_[i] = law_.sigma * A_[i];
        A_fixed_ += A_[i];
      }
    } else {
      K_p_ -= k_[i];
      S_p_ -= k_[i] * x_[i];
      ++updates_;
    }
    if (intact_[i]) { intact_[i] = 0; --n_intact_; }
    phase_[i] = Phase::slipping;
    slipping_.push_back(i);
    F_sl_ += (always_ && nonlinear_) ? f_sl_[i] : law_.epsilon * f_s_[i];
  }

  // Aggregate sums drift by rounding over many updates: recompute them exactly now and then
  // (amortised O(1) per update).
  void maybe_resum() {
    if (updates_ < std::max<std::int64_t>(1024, static_cast<std::int64_t>(A0_.size()))) return;
    updates_ = 0;
    double K = 0, S = 0, A = 0;
    for (std::size_t i = 0; i < A0_.size(); ++i) {
      if (nl_pos_[i] != npos) continue;
      if (phase_[i] == Phase::pinned) { K += k_[i]; S += k_[i] * x_[i]; }
      A += (always_ && nonlinear_) ? A_sl_[i] : A_[i];
    }
    K_p_ = K; S_p_ = S; A_fixed_ = A;
  }

  const Experiment& e_;
  const ModelSettings& m_;
  ContactLaw law_;
  bool always_, nonlinear_;
  std::vector<double> A0_, w_, c_, d_s_, k_, f_s_, A_, x_, f_sl_, A_sl_, k_sl_;
  std::vector<Phase> phase_;
  std::vector<std::uint8_t> intact_;
  std::vector<std::size_t> nl_pos_;
  // Nonlinear (never-slipped, or pinned under area_law: always) junctions, packed.
  std::vector<std::uint32_t> nl_idx_;
  std::vector<double> nl_w_, nl_c_, nl_x_, nl_A0_;
  std::optional<UniversalForceLaw> table_;
  std::optional<BinnedUniversalSum> binned_;  // large N under until_first_slip
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap_;
  std::vector<std::uint32_t> slipping_;
  double K_p_ = 0, S_p_ = 0, F_sl_ = 0, A_fixed_ = 0;
  std::int64_t n_intact_ = 0, slips_ = 0, repins_ = 0, updates_ = 0;
  mutable std::int64_t force_evals_ = 0;
};

}  // namespace

RunInfo integrate_event(const Scene& scene, Recorder& rec, const RunLimits& limits) {
  const auto& e = scene.experiment;
  const auto& m = scene.model;
  RunInfo info = initial_info(scene);
  const double M = e.mass_kg, kL = e.k_L, v = e.v, eta = m.eta;
  const double L = v * info.T0;  // length scale of the scaled state
  const double v_repin = m.c_min * v;
  const double tol = scene.solver.tolerance;
  const double t_stop = scene.stop.time;

  EventModel model(scene);
  auto rhs = [&](const State& y, State& dy, double t) {
    const double X = y[0] * L, V = y[1] * v;
    dy[0] = V / L;
    dy[1] = ((kL * (v * t - X) - model.force(X)) / M - eta * V) / v;
  };
  auto sample_at = [&](double t, const State& y) {
    const double X = y[0] * L;
    return Sample{t, X, y[1] * v, kL * (v * t - X), model.area(X), model.n_slipping(), model.n_intact()};
  };

  auto stepper = odeint::make_dense_output(tol, tol, odeint::runge_kutta_dopri5<State>());
  State y{0.0, 0.0};
  double t = 0.0;
  stepper.initialize(y, t, info.T0 / 100.0);
  while (rec.next_sample_time() <= 0.0) rec.sample(sample_at(0.0, y));

  // Event functions on the dense output; each says in which direction it fires.
  enum Kind { kThreshold, kSlowUp, kSlowDown, kExtremumUp, kExtremumDown };
  struct Found { double t; Kind kind; };
  State ys;
  // Event function k on a state at time tt (scaled units).
  auto value = [&](Kind k, const State& st) {
    switch (k) {
      case kThreshold: return st[0] * L - model.next_threshold();  // fires upward
      case kSlowUp: return st[1] * v - v_repin;                     // fires downward
      case kSlowDown: return st[1] * v + v_repin;                   // fires upward
      case kExtremumUp:                                             // upward: Q maximum
      case kExtremumDown: return st[1] * v - v;                     // downward: Q minimum
    }
    return 0.0;
  };
  auto eval = [&](Kind k, double tt) {
    stepper.calc_state(tt, ys);
    return value(k, ys);
  };
  auto fires = [](Kind k, double ga, double gb) {
    const bool up = k == kThreshold || k == kSlowDown || k == kExtremumUp;
    return up ? (ga < 0 && gb >= 0) : (ga > 0 && gb <= 0);
  };
  constexpr int kProbe = 8;  // interior probes: catch crossings that revert within one step

  std::int64_t steps = 0;
  bool finished = false;
  LimitGuard guard(limits);
  while (!finished && !rec.done()) {
    if ((info.stopped_by = guard.check(model.slips())) != LimitHit::none) {
      t = std::min(stepper.current_time(), t_stop);  // everything up to here is recorded
      break;
    }
    const auto [t0, t1] = stepper.do_step(rhs);
    ++steps;
    double t_lo = t0;
    for (;;) {
      const double t_hi = std::min(t1, t_stop);
      Kind active[5] = {kExtremumUp, kExtremumDown};
      int n_active = 2;
      if (model.has_threshold()) active[n_active++] = kThreshold;
      if (model.n_slipping() > 0) { active[n_active++] = kSlowUp; active[n_active++] = kSlowDown; }
      // Dense-output states at the probes, shared by every event function.
      double probe_t[kProbe + 1];
      State probe_y[kProbe + 1];
      for (int j = 0; j <= kProbe; ++j) {
        probe_t[j] = t_lo + (t_hi - t_lo) * j / kProbe;
        stepper.calc_state(probe_t[j], probe_y[j]);
      }
      std::optional<Found> first;
      for (int a = 0; a < n_active; ++a) {
        const Kind k = active[a];
        double ga = value(k, probe_y[0]);
        for (int j = 1; j <= kProbe; ++j) {
          if (first && probe_t[j - 1] >= first->t) break;
          const double gb = value(k, probe_y[j]);
          if (fires(k, ga, gb)) {
            boost::math::tools::eps_tolerance<double> etol(50);
            std::uintmax_t it = 100;
            auto fn = [&](double tt) { return eval(k, tt); };
            const auto r = boost::math::tools::toms748_solve(fn, probe_t[j - 1], probe_t[j], ga, gb, etol, it);
            // Take the side of the bracket where the event has happened.
            const double te = fires(k, ga, fn(r.first)) ? r.first : r.second;
            if (!first || te < first->t) first = Found{te, k};
            break;
          }
          ga = gb;
        }
      }
      const double t_cut = first ? first->t : t_hi;
      while (rec.next_sample_time() <= t_cut) {
        const double ts = rec.next_sample_time();
        stepper.calc_state(ts, ys);
        rec.sample(sample_at(ts, ys));
      }
      if (!first) {
        if (t1 >= t_stop) {
          stepper.calc_state(t_stop, y);
          t = t_stop;
          finished = true;
        }
        break;
      }
      stepper.calc_state(first->t, y);
      t = first->t;
      if (first->kind == kExtremumUp || first->kind == kExtremumDown) {
        const double X = y[0] * L;
        rec.extremum({t, kL * (v * t - X), model.area(X), first->kind == kExtremumUp});
        if (rec.done()) { finished = true; break; }
        t_lo = t;
        continue;  // no discontinuity: keep the step
      }
      // A discontinuity of the force law: apply it and restart the integrator there.
      const double X = y[0] * L;
      const std::int64_t new_slips = first->kind == kThreshold ? model.slip_crossed(X) : 0;
      const bool stick = model.n_slipping() > 0 && std::abs(y[1] * v) < v_repin;
      if (stick) model.repin_all(X);
      if (new_slips > 0 || stick) {
        rec.population({t, new_slips, stick, model.n_intact()});
        if (rec.done()) finished = true;
      }
      if (!std::isfinite(y[0]) || !std::isfinite(y[1]))
        throw SolverError("event solver: non-finite state at t = " + std::to_string(t) + " s");
      // A threshold at or behind X would never fire (its event function starts ≥ 0): the slip
      // distance (1 − ε) f_s/k of a repinned junction is below the resolution of X. Never the
      // case in a physical population; refused rather than letting the junction overload.
      if (model.has_threshold() && model.next_threshold() <= X) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      "event solver: a junction's slip distance is below the resolution of the slider position "
                      "(X = %.3g m) at t = %.3g s: check the junction areas and sigma_exp",
                      X, t);
        throw SolverError(msg);
      }
      stepper.initialize(y, t, stepper.current_time_step());
      break;
    }
    if (t >= t_stop) finished = true;
  }
  info.t_end = t;
  info.stats.steps = steps;
  info.stats.force_evals = model.force_evals();
  info.stats.slips = model.slips();
  info.stats.repins = model.repins();
  info.max_f_over_sigmaA = model.slips() > 0 ? 1.0 : 0.0;  // f = σA exactly at each slip
  info.max_f_over_sigma_exp_A = info.max_f_over_sigmaA / m.epsilon;
  return info;
}

}  // namespace asperity
