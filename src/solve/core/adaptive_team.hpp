#pragma once
// How many OpenMP threads a short, repeated parallel loop uses, decided by measuring it. On a
// quiet machine the widest team wins; when another process holds a core, a team member shares
// that core and every barrier waits for it to be scheduled again (a time slice, milliseconds,
// against loops of tens of microseconds: many times slower than one thread, docs/performance.md),
// and one thread wins. Each loop kind keeps its own AdaptiveTeam: the cost per unit of work of
// the last regions run with one thread and with the whole team (moving averages); the loop runs
// with the cheaper, and now and then (more rarely as the other keeps losing, at most 1/20 of the
// time spent) tries the other, so a change of load is seen within about a second of running.
// The loops split their work in fixed blocks (the same bits on any number of threads), so the
// choice changes no result. Not thread-safe: one team per loop site of one solver.
#include <chrono>

namespace asperity {

class AdaptiveTeam {
 public:
  // max_threads: the team's width (omp_get_max_threads() at the solver's construction, i.e.
  // -j); min_work: below it a region runs on one thread and is not measured.
  AdaptiveTeam(int max_threads, double min_work) : max_(max_threads > 1 ? max_threads : 1), min_work_(min_work) {}

  // One parallel region of `work` units (any unit proportional to its cost): threads() for its
  // num_threads clause; its time is recorded when it ends.
  class Region {
   public:
    Region(AdaptiveTeam& team, double work)
        : team_(team), work_(work), threads_(team.choose(work)), start_(std::chrono::steady_clock::now()) {}
    Region(const Region&) = delete;
    Region& operator=(const Region&) = delete;
    ~Region() {
      const std::chrono::duration<double> s = std::chrono::steady_clock::now() - start_;
      team_.record(threads_, s.count(), work_);
    }
    int threads() const { return threads_; }

   private:
    AdaptiveTeam& team_;
    double work_;
    int threads_;
    std::chrono::steady_clock::time_point start_;
  };

  int max_threads() const { return max_; }
  // Regions run on the whole team / on one thread (measured ones), for benchmarks.
  long long wide_regions() const { return wide_; }
  long long narrow_regions() const { return narrow_; }
  double seconds() const { return seconds_; }  // wall time in all regions, measured or not

  int choose(double work);
  void record(int threads, double seconds, double work);

 private:
  int max_;
  double min_work_;
  bool wide_now_ = true;       // the current choice: the whole team
  bool probing_ = false;       // this region tries the other choice
  double cost_[2] = {-1, -1};  // s per unit of work, [0] one thread, [1] the team; < 0: unknown
  double last_s_[2] = {0, 0};  // the last measured region's duration, by choice
  double since_probe_s_ = 0;   // time spent in measured regions since the last probe
  double probe_after_s_ = 0;   // the next probe once since_probe_s_ reaches this
  long long wide_ = 0, narrow_ = 0;
  double seconds_ = 0;
};

}  // namespace asperity
