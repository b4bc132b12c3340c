#include "bench/timed_run.hpp"

#include <time.h>

#include <algorithm>
#include <utility>

#include "observe/simulate.hpp"

namespace asperity {

double median(std::vector<double> xs) {
  if (xs.empty()) return 0;
  std::sort(xs.begin(), xs.end());
  const std::size_t n = xs.size();
  return n % 2 ? xs[n / 2] : 0.5 * (xs[n / 2 - 1] + xs[n / 2]);
}

namespace {

double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// One run: its result and the process CPU time it took.
struct OneRun {
  RunResult r;
  double cpu_s;
};
OneRun one_run(const Scene& scene) {
  const double c0 = process_cpu_s();
  RunResult r = simulate(scene);
  return OneRun{std::move(r), process_cpu_s() - c0};
}

// Accumulates the runs of one scene.
struct Timings {
  TimedRun t;
  std::vector<double> walls, cpus;
  void add(OneRun&& x) {
    if (walls.empty()) {
      t.obs = x.r.obs;
      t.series_bytes = x.r.recorder.series().capacity() * sizeof(Sample);
    }
    walls.push_back(x.r.obs.wall_s);
    cpus.push_back(x.cpu_s);
  }
  TimedRun done() {
    t.wall_s = median(walls);
    t.cpu_s = median(cpus);
    t.repeats = static_cast<int>(walls.size());
    return t;
  }
};

}  // namespace

TimedRun timed_run(const Scene& scene, int repeats, double repeat_below_s) {
  Timings t;
  t.add(one_run(scene));
  if (t.walls.front() < repeat_below_s)
    while (static_cast<int>(t.walls.size()) < repeats) t.add(one_run(scene));
  return t.done();
}

std::pair<TimedRun, TimedRun> timed_pair(const Scene& a, const Scene& b, int repeats) {
  Timings ta, tb;
  for (int i = 0; i < repeats; ++i) {
    ta.add(one_run(a));
    tb.add(one_run(b));
  }
  return {ta.done(), tb.done()};
}

}  // namespace asperity
