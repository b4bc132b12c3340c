#pragma once
// The whole pipeline of one run, for every command that runs scenes (run, sweep, bench, ...):
// a Recorder configured from the scene, the solver the scene names, the observables.
#include "observe/observables.hpp"
#include "observe/recorder.hpp"
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
// Throws SolverError as integrate() does. wall_limit_s > 0: the run stops at the first sample
// after that much wall time, and recorder.timed_out() says so (sweeps' per-point limit).
RunResult simulate(const Scene& scene, double wall_limit_s = 0);

}  // namespace asperity
