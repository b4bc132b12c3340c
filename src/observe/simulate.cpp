#include "observe/simulate.hpp"

#include <chrono>
#include <utility>

namespace asperity {

Recorder make_recorder(const Scene& scene) {
  return Recorder(scene.output.every, !scene.output.series.empty(), scene.output.peak_min_drop,
                  scene.stop.at_first_peak, scene.stop.cycles);
}

RunResult simulate(const Scene& scene, double wall_limit_s) {
  Recorder rec = make_recorder(scene);
  RunLimits limits = run_limits(scene);
  const bool sweep_limit = wall_limit_s > 0 && wall_limit_s < limits.wall_time_s;
  if (sweep_limit) limits.wall_time_s = wall_limit_s;
  const auto t0 = std::chrono::steady_clock::now();
  RunInfo info = integrate(scene, rec, limits);
  if (info.stopped_by == LimitHit::wall_time && sweep_limit)
    rec.mark_timed_out();
  else if (info.stopped_by != LimitHit::none)
    throw SolverError(limit_message(scene, limits, info.stopped_by, info.t_end, info.stats.slips));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Observables obs = summarize(scene, info, rec, wall);
  return RunResult{std::move(info), std::move(rec), std::move(obs)};
}

}  // namespace asperity
