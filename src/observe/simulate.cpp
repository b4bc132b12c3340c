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
  const auto t0 = std::chrono::steady_clock::now();
  if (wall_limit_s > 0)
    rec.set_wall_deadline(t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(wall_limit_s)));
  RunInfo info = integrate(scene, rec);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Observables obs = summarize(scene, info, rec, wall);
  return RunResult{std::move(info), std::move(rec), std::move(obs)};
}

}  // namespace asperity
