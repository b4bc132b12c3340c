#pragma once
// One scene run for a benchmark: its observables and the median wall time of a few repeats
// (fast runs only: one run of a slow one is already a stable figure).
#include <vector>

#include "observe/observables.hpp"
#include "scene/scene.hpp"

namespace asperity {

struct TimedRun {
  Observables obs;        // of the first run (the runs are deterministic)
  double wall_s = 0;      // median wall time of integrate() over the repeats [s]
  int repeats = 1;
  std::size_t series_bytes = 0;  // memory held by the Recorder's series [bytes]
};

// Runs `scene` once; when that took less than `repeat_below_s`, runs it until `repeats` runs
// in all and reports the median wall time.
TimedRun timed_run(const Scene& scene, int repeats, double repeat_below_s = 1.0);

double median(std::vector<double> xs);

}  // namespace asperity
