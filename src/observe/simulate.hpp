#pragma once
// The whole pipeline of one run, for every command that runs scenes (run, sweep, bench, ...):
// a Recorder configured from the scene, the solver the scene names, the observables.
#include "observe/observables.hpp"
#include "observe/recorder.hpp"
#include "observe/run_monitor.hpp"
#include "scene/scene.hpp"
#include "solve/integrate.hpp"

namespace asperity {

// Recorder(every, keep_series = !series.empty(), peak_min_drop, stop.at_first_peak, stop.cycles).
Recorder make_recorder(const Scene& scene);

struct RunResult {
  RunInfo info;
  Recorder recorder;
  Observables obs;
};

// Integrates the scene and summarizes it; obs.wall_s is the wall-clock time of integrate().
// Throws SolverError as integrate() does, and when the run reached stop.wall_time or
// stop.max_slips (limit_message). wall_limit_s > 0 (a sweep's per-point limit), when below
// stop.wall_time: the solver stops once that much wall time has passed, and
// recorder.timed_out() says so instead of an exception. `monitor` (optional) is polled during
// the run (progress, interruption: RunInterrupted).
RunResult simulate(const Scene& scene, double wall_limit_s = 0, const RunMonitor* monitor = nullptr);

}  // namespace asperity
