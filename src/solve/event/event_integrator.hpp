#pragma once
// The event method's integrator (solver.method: event), generic over the junction model: the
// reference's dt → 0 limit, integrated with an adaptive Dormand–Prince 5(4) method (Boost.Odeint,
// dense output) between events located on its dense output (Boost.Math TOMS 748): a junction
// reaching its slip threshold, the slider slowing below c_min·v (repinning), and the slider
// velocity crossing v (extrema of Q). Between events the state is smooth, so steps are long
// during slow loading and short only where needed. Private to the event steppers' .cpp files
// (keeps Boost.Odeint out of their headers).
#include <algorithm>
#include <array>
#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "solve/core/junction_model.hpp"
#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"

namespace asperity {
namespace event_detail {

namespace odeint = boost::numeric::odeint;
using State = std::array<double, 2>;  // (X / L, V / v): scaled so one tolerance fits both
using Dense = odeint::result_of::make_dense_output<odeint::runge_kutta_dopri5<State>>::type;

// Event functions on the dense output; each says in which direction it fires.
// kThresholdBelow: a pinned junction whose force grows as X decreases (interacting junctions only).
enum Kind { kThreshold, kSlowUp, kSlowDown, kExtremumUp, kExtremumDown, kThresholdBelow };
inline bool fires(Kind k, double ga, double gb) {
  const bool up = k == kThreshold || k == kSlowDown || k == kExtremumUp;
  return up ? (ga < 0 && gb >= 0) : (ga > 0 && gb <= 0);
}
constexpr int kProbe = 8;  // interior probes: catch crossings that revert within one step

// Dense-output states at the probes of a step, shared by every event function.
struct Probes {
  double t[kProbe + 1];
  State y[kProbe + 1];
};

// The earliest event found in a step so far.
struct Found {
  double t;
  Kind kind;
};

}  // namespace event_detail

// The event method over a junction model (solve/core/junction_model.hpp: EventJunctions,
// InteractingJunctions).
template <JunctionModel Junctions>
struct EventIntegrator {
  using State = event_detail::State;
  using Dense = event_detail::Dense;
  using Kind = event_detail::Kind;
  // Any further arguments go to the junction model's constructor.
  template <class... Args>
  explicit EventIntegrator(const Problem& p, Args&&... junction_args)
      : p(p),
        L(p.slider.v * p.T0),
        junctions(p, std::forward<Args>(junction_args)...),
        stepper(boost::numeric::odeint::make_dense_output(p.solver.tolerance, p.solver.tolerance,
                                                          boost::numeric::odeint::runge_kutta_dopri5<State>())) {}

  // Not const: a junction model may solve, and cache, as it is asked for F(X) and A(X).
  void rhs(const State& y, State& dy, double tt) {
    const double X = y[0] * L, V = y[1] * p.slider.v;
    dy[0] = V / L;
    dy[1] = p.slider.acceleration(p.slider.loading_force(tt, X), junctions.force(X), V) / p.slider.v;
  }
  Sample sample_at(double ts, const State& st) {
    const double X = st[0] * L;
    return Sample{ts,
                  X,
                  st[1] * p.slider.v,
                  p.slider.loading_force(ts, X),
                  junctions.area(X),
                  junctions.n_slipping(),
                  junctions.n_intact()};
  }
  // Event function k on a state (scaled units).
  double value(Kind k, const State& st) const {
    const double v = p.slider.v;
    switch (k) {
      case event_detail::kThreshold:
        return st[0] * L - junctions.next_threshold();  // fires upward
      case event_detail::kThresholdBelow:
        return st[0] * L - junctions.next_threshold_below();  // downward
      case event_detail::kSlowUp:
        return st[1] * v - p.repin_speed();  // fires downward
      case event_detail::kSlowDown:
        return st[1] * v + p.repin_speed();  // fires upward
      case event_detail::kExtremumUp:        // upward: Q maximum
      case event_detail::kExtremumDown:
        return st[1] * v - v;  // downward: Q minimum
    }
    return 0.0;
  }
  void advance(RunObserver& out);  // one accepted step, and every event inside it
  // The steps of advance, each on the step the stepper holds.
  double value_at(Kind k, double tt) {  // event function k on the dense output at tt
    stepper.calc_state(tt, ys);
    return value(k, ys);
  }
  std::optional<event_detail::Found> first_event(double t_lo, double t_hi);
  void earliest_crossing(Kind k, const event_detail::Probes& probes, std::optional<event_detail::Found>& first);
  void crossing_at_turn(Kind k, const event_detail::Probes& probes, int j, double ga, double& gb, double& t_b);
  void sample_until(RunObserver& out, double t_cut);
  bool record_extremum(RunObserver& out, bool maximum);
  void apply_discontinuity(RunObserver& out, Kind kind);
  void start(RunObserver& out) {  // the samples due at t = 0
    stepper.initialize(y, t, p.T0 / 100.0);
    while (out.next_sample_time() <= 0.0) out.sample(sample_at(0.0, y));
  }
  void stop_early() { t = std::min(stepper.current_time(), p.t_stop); }
  void finish(RunInfo& info) const {
    info.t_end = t;
    info.stats.steps = steps;
    info.stats.force_evals = junctions.force_evals();
    info.stats.slips = junctions.slips();
    info.stats.repins = junctions.repins();
    info.max_f_over_sigmaA = junctions.slips() > 0 ? 1.0 : 0.0;  // f = σA exactly at each slip
    info.max_f_over_sigma_exp_A = info.max_f_over_sigmaA / p.law.epsilon;
  }

  const Problem& p;
  const double L;  // length scale of the scaled state
  Junctions junctions;
  Dense stepper;
  State y{0.0, 0.0}, ys{};
  double t = 0.0;
  std::int64_t steps = 0;
  bool finished = false;
};

template <JunctionModel Junctions>
void EventIntegrator<Junctions>::advance(RunObserver& out) {
  using namespace event_detail;
  const double t_stop = p.t_stop;
  auto system = [this](const State& yy, State& dy, double tt) { rhs(yy, dy, tt); };
  const auto [t0, t1] = stepper.do_step(system);
  ++steps;
  double t_lo = t0;
  for (;;) {
    const double t_hi = std::min(t1, t_stop);
    const std::optional<Found> first = first_event(t_lo, t_hi);
    sample_until(out, first ? first->t : t_hi);
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
      if (record_extremum(out, first->kind == kExtremumUp)) {
        finished = true;
        break;
      }
      t_lo = t;
      continue;  // no discontinuity: keep the step
    }
    apply_discontinuity(out, first->kind);
    break;
  }
  if (t >= t_stop) finished = true;
}

// The earliest event in [t_lo, t_hi] of those that can happen now.
template <JunctionModel Junctions>
std::optional<event_detail::Found> EventIntegrator<Junctions>::first_event(double t_lo, double t_hi) {
  using namespace event_detail;
  Kind active[6] = {kExtremumUp, kExtremumDown};
  int n_active = 2;
  if (junctions.has_threshold()) active[n_active++] = kThreshold;
  if (junctions.has_threshold_below()) active[n_active++] = kThresholdBelow;
  if (junctions.n_slipping() > 0) {
    active[n_active++] = kSlowUp;
    active[n_active++] = kSlowDown;
  }
  Probes probes;
  for (int j = 0; j <= kProbe; ++j) {
    probes.t[j] = t_lo + (t_hi - t_lo) * j / kProbe;
    stepper.calc_state(probes.t[j], probes.y[j]);
  }
  std::optional<Found> first;
  for (int a = 0; a < n_active; ++a) earliest_crossing(active[a], probes, first);
  return first;
}

// The first crossing of event function k between the probes, located by TOMS 748; kept in `first`
// when earlier than the one there.
template <JunctionModel Junctions>
void EventIntegrator<Junctions>::earliest_crossing(Kind k, const event_detail::Probes& probes,
                                                   std::optional<event_detail::Found>& first) {
  using namespace event_detail;
  double ga = value(k, probes.y[0]);
  for (int j = 1; j <= kProbe; ++j) {
    if (first && probes.t[j - 1] >= first->t) break;
    double gb = value(k, probes.y[j]);
    double t_b = probes.t[j];
    crossing_at_turn(k, probes, j, ga, gb, t_b);
    if (fires(k, ga, gb)) {
      boost::math::tools::eps_tolerance<double> etol(50);
      std::uintmax_t it = 100;
      auto fn = [&](double tt) { return value_at(k, tt); };
      const auto r = boost::math::tools::toms748_solve(fn, probes.t[j - 1], t_b, ga, gb, etol, it);
      // Take the side of the bracket where the event has happened.
      const double te = fires(k, ga, fn(r.first)) ? r.first : r.second;
      if (!first || te < first->t) first = Found{te, k};
      break;
    }
    ga = gb;
  }
}

// A slip position X crosses and re-crosses inside one probe interval when X turns back there (the
// slider's velocity changes sign: undamped stick-slip, η = 0). X − X_s is monotone between zeros
// of V, so its extremum is at the root of V: a threshold reached there fires in [t_{j-1}, that
// root], which becomes the interval's end (gb, t_b).
template <JunctionModel Junctions>
void EventIntegrator<Junctions>::crossing_at_turn(Kind k, const event_detail::Probes& probes, int j, double ga,
                                                  double& gb, double& t_b) {
  using namespace event_detail;
  const bool x_max = k == kThreshold && probes.y[j - 1][1] > 0 && probes.y[j][1] < 0;
  const bool x_min = k == kThresholdBelow && probes.y[j - 1][1] < 0 && probes.y[j][1] > 0;
  if (fires(k, ga, gb) || !(x_max || x_min)) return;
  boost::math::tools::eps_tolerance<double> etol(50);
  std::uintmax_t it = 100;
  auto velocity = [&](double tt) {
    stepper.calc_state(tt, ys);
    return ys[1];
  };
  const auto r = boost::math::tools::toms748_solve(velocity, probes.t[j - 1], probes.t[j], probes.y[j - 1][1],
                                                   probes.y[j][1], etol, it);
  for (const double t_turn : {r.first, r.second}) {  // either side of the turning point
    const double g_turn = value_at(k, t_turn);
    if (fires(k, ga, g_turn)) {
      gb = g_turn;
      t_b = t_turn;
      break;
    }
  }
}

// The samples due up to t_cut, from the dense output.
template <JunctionModel Junctions>
void EventIntegrator<Junctions>::sample_until(RunObserver& out, double t_cut) {
  while (out.next_sample_time() <= t_cut) {
    const double ts = out.next_sample_time();
    stepper.calc_state(ts, ys);
    out.sample(sample_at(ts, ys));
  }
}

// An extremum of Q at the current state; true when the observer has seen enough.
template <JunctionModel Junctions>
bool EventIntegrator<Junctions>::record_extremum(RunObserver& out, bool maximum) {
  const double X = y[0] * L;
  out.extremum({t, p.slider.loading_force(t, X), junctions.area(X), maximum});
  return out.done();
}

// A discontinuity of the force law at the current state (a slip or a repin): apply it and restart
// the integrator there.
template <JunctionModel Junctions>
void EventIntegrator<Junctions>::apply_discontinuity(RunObserver& out, Kind kind) {
  using namespace event_detail;
  const double X = y[0] * L;
  const std::int64_t new_slips = (kind == kThreshold || kind == kThresholdBelow) ? junctions.slip_crossed(X) : 0;
  const bool stick = junctions.n_slipping() > 0 && std::abs(y[1] * p.slider.v) < p.repin_speed();
  if (stick) junctions.repin_all(X);
  if (new_slips > 0 || stick) {
    out.population({t, new_slips, stick, junctions.n_intact()});
    if (out.done()) finished = true;
  }
  if (!std::isfinite(y[0]) || !std::isfinite(y[1]))
    throw SolverError("event solver: non-finite state at t = " + std::to_string(t) + " s");
  // A threshold at or behind X would never fire (its event function starts ≥ 0): the slip
  // distance (1 − ε) f_s/k of a repinned junction is below the resolution of X. Never the
  // case in a physical population; refused rather than letting the junction overload.
  if (junctions.has_threshold() && junctions.next_threshold() <= X) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "event solver: a junction's slip distance is below the resolution of the slider position "
                  "(X = %.3g m) at t = %.3g s: check the junction areas and sigma_exp",
                  X, t);
    throw SolverError(msg);
  }
  if (junctions.has_threshold_below() && junctions.next_threshold_below() >= X)
    throw SolverError("event solver: a junction's slip position below X is at or above X = " + std::to_string(X) +
                      " m");
  stepper.initialize(y, t, stepper.current_time_step());
}

}  // namespace asperity
