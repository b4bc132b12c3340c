#pragma once
// Event-driven method (`solver.method: event`): the reference's dt → 0 limit, integrated with
// an adaptive Dormand–Prince 5(4) method between events that are located on its dense output.
#include <cstdint>
#include <memory>

#include "solve/core/observer.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_info.hpp"

namespace asperity {

class EventStepper {
 public:
  // Throws SolverError when the universal law's table cannot reach the needed accuracy.
  explicit EventStepper(const Problem& problem);
  ~EventStepper();

  void start(RunObserver& out);  // the samples due at t = 0
  bool finished() const;
  std::int64_t slips() const;
  void advance(RunObserver& out);  // one accepted step, and every event inside it
  void stop_early();               // a resource limit: everything up to here is recorded
  void finish(RunInfo& info) const;

 private:
  struct Impl;  // keeps Boost.Odeint out of this header
  std::unique_ptr<Impl> impl_;
};

}  // namespace asperity
