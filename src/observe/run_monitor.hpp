#pragma once
// Watching one run from outside: progress lines for a long run, Ctrl-C from Python or a
// terminal. The monitor sees how far the run has got in simulated time and may interrupt it;
// simulate() polls it from inside the solver loop, so even a 10^6-junction run answers within
// a fraction of a second.
#include <functional>
#include <stdexcept>

namespace asperity {

struct RunMonitor {
  // Called with the simulated time reached (s) and the scene's stop.time (s), at most once per
  // period_s of wall time; returns false to interrupt the run (simulate throws RunInterrupted).
  std::function<bool(double t_s, double stop_time_s)> poll;
  double period_s = 0.25;
};

// A run the monitor interrupted; nothing of it is written.
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace asperity
