#pragma once
// Receives what a solver sees (samples at fixed instants, extrema of Q) and decides when the
// run may stop. Solver-independent: both solvers feed it the same way.
#include <cstdint>
#include <limits>
#include <vector>

#include "observe/sample.hpp"

namespace asperity {

struct Peak {        // a confirmed macroscopic peak of Q and the trough that follows it
  Extremum max, min;
};

class Recorder {
 public:
  // every [s]: sampling interval; keep_series: store every sample (else only the loading
  // branch, which the quadratic fit needs); min_drop: relative drop that confirms a peak;
  // stop_at_first_peak / stop_after_cycles: stop conditions (cycles < 0: none).
  Recorder(double every, bool keep_series, double min_drop, bool stop_at_first_peak,
           int stop_after_cycles);

  // Time of the next sample the solver must deliver.
  double next_sample_time() const { return static_cast<double>(next_index_) * every_; }
  std::int64_t next_sample_index() const { return next_index_; }
  void sample(const Sample& s);
  void extremum(const Extremum& e);
  bool done() const { return done_; }
  // A sweep's per-point time limit ended the run (the solver checks it: solve/run_limits.hpp).
  void mark_timed_out() { done_ = timed_out_ = true; }
  bool timed_out() const { return timed_out_; }

  const std::vector<Sample>& series() const { return series_; }
  const std::vector<Sample>& loading_branch() const { return loading_; }
  const std::vector<Peak>& peaks() const { return peaks_; }
  const Sample& last() const { return last_; }
  // Largest Q seen in any sample or extremum (the peak when no drop confirmed one).
  const Extremum& highest() const { return highest_; }
  double every() const { return every_; }

 private:
  double every_;
  bool keep_series_;
  double min_drop_;
  bool stop_at_first_peak_;
  int stop_after_cycles_;
  std::int64_t next_index_ = 0;
  bool done_ = false;
  bool timed_out_ = false;
  bool have_candidate_ = false;
  Extremum candidate_{};  // latest maximum not yet confirmed by a drop
  std::vector<Sample> series_, loading_;
  std::vector<Peak> peaks_;
  Sample last_{};
  Extremum highest_{0, -std::numeric_limits<double>::infinity(), 0, true};
};

}  // namespace asperity
