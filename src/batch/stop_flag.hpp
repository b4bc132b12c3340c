#pragma once
// A cooperative stop for a batch of runs (the Python module's Ctrl-C; the command line is ended
// by the signal itself): once the flag is set a batch starts no new run, and every run in flight
// polls it through monitor() and throws RunInterrupted within ~0.05 s, so a sweep or a fit stops
// well within a second and keeps (in its journal) whatever finished.
#include <atomic>

#include "observe/run_monitor.hpp"

namespace asperity {

class StopFlag {
 public:
  explicit StopFlag(const std::atomic<bool>* flag = nullptr);  // null: never stops

  bool requested() const { return flag_ != nullptr && flag_->load(std::memory_order_relaxed); }
  // What simulate() should poll; null without a flag (a run then never polls).
  const RunMonitor* monitor() const { return flag_ ? &monitor_ : nullptr; }

 private:
  const std::atomic<bool>* flag_;
  RunMonitor monitor_;  // polls flag_ only (copies stay valid)
};

}  // namespace asperity
