#include "observe/simulate.hpp"

#include <chrono>
#include <utility>

namespace asperity {

Recorder make_recorder(const Scene& scene) {
  return Recorder(scene.output.every, !scene.output.series.empty(), scene.output.peak_min_drop,
                  scene.stop.at_first_peak, scene.stop.cycles);
}

RunResult simulate(const Scene& scene) {
  Recorder rec = make_recorder(scene);
  const auto t0 = std::chrono::steady_clock::now();
  RunInfo info = integrate(scene, rec);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Observables obs = summarize(scene, info, rec, wall);
  return RunResult{std::move(info), std::move(rec), std::move(obs)};
}

}  // namespace asperity
