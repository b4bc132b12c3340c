#include "bench/timed_run.hpp"

#include <algorithm>

#include "observe/simulate.hpp"

namespace asperity {

double median(std::vector<double> xs) {
  if (xs.empty()) return 0;
  std::sort(xs.begin(), xs.end());
  const std::size_t n = xs.size();
  return n % 2 ? xs[n / 2] : 0.5 * (xs[n / 2 - 1] + xs[n / 2]);
}

TimedRun timed_run(const Scene& scene, int repeats, double repeat_below_s) {
  RunResult first = simulate(scene);
  TimedRun t;
  t.obs = first.obs;
  t.series_bytes = first.recorder.series().capacity() * sizeof(Sample);
  std::vector<double> walls{first.obs.wall_s};
  if (first.obs.wall_s < repeat_below_s)
    while (static_cast<int>(walls.size()) < repeats) walls.push_back(simulate(scene).obs.wall_s);
  t.wall_s = median(walls);
  t.repeats = static_cast<int>(walls.size());
  return t;
}

}  // namespace asperity
