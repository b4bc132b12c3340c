#pragma once
// One scene run for a benchmark: its observables and the median wall time of a few repeats
// (fast runs only: one run of a slow one is already a stable figure).
#include <utility>
#include <vector>

#include "observe/observables.hpp"
#include "scene/scene.hpp"

namespace asperity {

struct TimedRun {
  Observables obs;    // of the first run (the runs are deterministic)
  double wall_s = 0;  // median wall time of integrate() over the repeats [s]
  double cpu_s = 0;   // median process CPU time of the same runs [s] (less sensitive to
                      // other jobs on a shared machine than the wall time)
  int repeats = 1;
  std::size_t series_bytes = 0;  // memory held by the Recorder's series [bytes]
};

// Runs `scene` once; when that took less than `repeat_below_s`, runs it until `repeats` runs
// in all and reports the median wall time.
TimedRun timed_run(const Scene& scene, int repeats, double repeat_below_s = 1.0);

// Two scenes timed in alternation (A B A B ...), `repeats` runs each, so that a change of the
// machine's load during the measurement affects both alike.
std::pair<TimedRun, TimedRun> timed_pair(const Scene& a, const Scene& b, int repeats);

double median(std::vector<double> xs);

}  // namespace asperity
