#include "observe/simulate.hpp"

#include <chrono>
#include <cstdint>

#include <utility>
#include "io/numbers.hpp"
#include "solve/core/openmp_fork.hpp"

namespace asperity {

Recorder make_recorder(const Scene& scene) {
  return Recorder(scene.output.every, !scene.output.series.empty(), scene.output.peak_min_drop,
                  scene.stop.at_first_peak, scene.stop.cycles);
}

namespace {

using Clock = std::chrono::steady_clock;

// The recorder, seen through a monitor: forwards every report and, from done() (asked before
// every solver step), polls the monitor once per period. done() is const in the Observer
// concept; the poll state is mutable because polling is not part of the recorder's value.
class MonitoredRecorder {
 public:
  MonitoredRecorder(Recorder& rec, const RunMonitor& monitor, double stop_time_s)
      : rec_(rec), monitor_(monitor), stop_time_s_(stop_time_s), next_poll_(Clock::now()) {}

  void sample(const Sample& s) {
    t_ = s.t;
    rec_.sample(s);
  }
  void extremum(const Extremum& e) {
    t_ = e.t;
    rec_.extremum(e);
  }
  void population(const PopulationChange& c) {
    t_ = c.t;
    rec_.population(c);
  }
  double next_sample_time() const { return rec_.next_sample_time(); }
  bool done() const {
    if (rec_.done() || interrupted_) return true;
    if ((++calls_ & 63) != 0) return false;  // a clock read per 64 steps keeps the poll free
    const auto now = Clock::now();
    if (now < next_poll_) return false;
    next_poll_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(monitor_.period_s));
    interrupted_ = !monitor_.poll(t_, stop_time_s_);
    return interrupted_;
  }
  bool interrupted() const { return interrupted_; }

 private:
  Recorder& rec_;
  const RunMonitor& monitor_;
  double stop_time_s_;
  double t_ = 0;
  mutable Clock::time_point next_poll_;
  mutable std::uint64_t calls_ = 0;
  mutable bool interrupted_ = false;
};

}  // namespace

RunResult simulate(const Scene& scene, double wall_limit_s, const RunMonitor* monitor) {
  guard_openmp_against_fork();  // a process forked after this run keeps working (Python's os.fork)
  Recorder rec = make_recorder(scene);
  RunLimits limits = run_limits(scene);
  const bool sweep_limit = wall_limit_s > 0 && wall_limit_s < limits.wall_time_s;
  if (sweep_limit) limits.wall_time_s = wall_limit_s;
  const auto t0 = Clock::now();
  RunInfo info;
  if (monitor && monitor->poll) {
    MonitoredRecorder watched(rec, *monitor, scene.stop.time);
    info = integrate(scene, watched, limits);
    if (watched.interrupted())
      throw RunInterrupted("run interrupted at simulated t = " + io::format_double(info.t_end) + " s");
  } else {
    info = integrate(scene, rec, limits);
  }
  if (info.stopped_by == LimitHit::wall_time && sweep_limit)
    rec.mark_timed_out();
  else if (info.stopped_by != LimitHit::none)
    throw SolverError(limit_message(scene, limits, info.stopped_by, info.t_end, info.stats.slips));
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  Observables obs = summarize(scene, info, rec, wall);
  return RunResult{std::move(info), std::move(rec), std::move(obs)};
}

}  // namespace asperity
