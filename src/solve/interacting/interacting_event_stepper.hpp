#pragma once
// The event method for interacting junctions (solver.method: event with model.interactions:
// elastic): EventIntegrator over InteractingJunctions. Same continuous model as
// InteractingReferenceStepper (its dt → 0 limit).
#include <chrono>
#include <cstdint>
#include <memory>

#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"
#include "solve/interacting/interacting_junctions.hpp"

namespace asperity {

class InteractingEventStepper {
 public:
  // single_from: see InteractingJunctions (benchmarks run the double-only solver beside).
  explicit InteractingEventStepper(const Problem& problem, std::size_t single_from = PinnedCompliance::kSingleFrom);
  ~InteractingEventStepper();

  void start(RunObserver& out);
  bool finished() const;
  std::int64_t slips() const;
  void advance(RunObserver& out);
  void stop_early();
  // The run's wall-time deadline (see InteractingJunctions::set_deadline): a step still going
  // then stops with WallTimeReached.
  void set_deadline(std::chrono::steady_clock::time_point deadline);
  void clear_deadline();
  void finish(RunInfo& info) const;

  const InteractingJunctions& junctions() const;
  InteractingJunctions& junctions();  // its forces at X solve (and cache)
  double X() const;                   // m, the slider position now

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace asperity
