#pragma once
// One run: a stepper advances a Problem and reports to an observer. integrate() is the loop
// every method shares (resource limits, the observer's stop); the method is chosen in the one
// switch of integrate(problem, observer) below. Adding a method = one stepper file (a type
// meeting the Stepper concept) plus one case there.
#include <chrono>
#include <concepts>
#include <cstdint>
#include <stdexcept>

#include "scene/scene.hpp"
#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"
#include "solve/core/run_limits.hpp"
#include "solve/event/event_stepper.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"
#include "solve/interacting/interacting_reference_stepper.hpp"
#include "solve/reference/reference_stepper.hpp"

namespace asperity {

// A method: constructed from a Problem, it reports the samples due at t = 0 (start), then
// advances by one step (with every event inside it) until finished(); stop_early() when a
// resource limit ends the run; finish() fills t_end, stats and the f/(σA) maxima.
template <class S>
concept Stepper = requires(S& s, const S& cs, RunObserver& out, RunInfo& info) {
  s.start(out);
  s.advance(out);
  s.stop_early();
  { cs.finished() } -> std::convertible_to<bool>;
  { cs.slips() } -> std::convertible_to<std::int64_t>;
  cs.finish(info);
};
static_assert(Stepper<ReferenceStepper> && Stepper<EventStepper> && Stepper<InteractingReferenceStepper> &&
              Stepper<InteractingEventStepper>);

// Runs `stepper` from t = 0 until stop.time, the observer's done(), or a resource limit of the
// problem (checked before every step; info.stopped_by says which, simulate() turns it into a
// SolverError).
template <Stepper S, Observer O>
RunInfo integrate(S& stepper, const Problem& problem, O& observer) {
  ObserverAdapter<O> out(observer);
  RunInfo info = initial_info(problem);
  LimitGuard guard(problem.limits);  // the start's work counts too
  // A stepper whose single steps can run long (avalanches) watches the deadline inside them.
  // (Cleared after the run: the stepper's solves may serve a caller after the deadline.)
  constexpr bool watches = requires {
    stepper.set_deadline(guard.deadline());
    stepper.clear_deadline();
  };
  if constexpr (watches) stepper.set_deadline(guard.deadline());
  try {
    stepper.start(out);
    while (!stepper.finished() && !observer.done()) {
      if ((info.stopped_by = guard.check(stepper.slips())) != LimitHit::none) {
        stepper.stop_early();
        break;
      }
      stepper.advance(out);
    }
  } catch (const WallTimeReached&) {
    // Stopped inside a step: the stepper's time is still that of the last step or event it
    // completed (no stop_early, which would move it to the step's end).
    info.stopped_by = LimitHit::wall_time;
  }
  if constexpr (watches) stepper.clear_deadline();
  stepper.finish(info);
  return info;
}

// The method problem.solver.method names, run on `problem`.
template <Observer O>
RunInfo integrate(const Problem& problem, O& observer) {
  if (problem.interacting()) {
    if (problem.solver.method == SolverMethod::reference) {
      InteractingReferenceStepper s(problem);
      return integrate(s, problem, observer);
    }
    try {
      InteractingEventStepper s(problem);  // its first event search counts (see its deadline)
      return integrate(s, problem, observer);
    } catch (const WallTimeReached&) {  // in that search: stopped at t = 0
      RunInfo info = initial_info(problem);
      info.stopped_by = LimitHit::wall_time;
      return info;
    }
  }
  switch (problem.solver.method) {
    case SolverMethod::reference: {
      ReferenceStepper s(problem);
      return integrate(s, problem, observer);
    }
    case SolverMethod::event: {
      EventStepper s(problem);
      return integrate(s, problem, observer);
    }
  }
  throw std::logic_error("integrate: unknown solver.method");
}

// The scene's run with `limits` (default: run_limits(scene)).
template <Observer O>
RunInfo integrate(const Scene& scene, O& observer, const RunLimits& limits) {
  return integrate(make_problem(scene, limits), observer);
}
template <Observer O>
RunInfo integrate(const Scene& scene, O& observer) {
  return integrate(scene, observer, run_limits(scene));
}

}  // namespace asperity
