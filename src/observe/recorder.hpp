#pragma once
// Receives what a solver sees (samples at fixed instants, extrema of Q, changes of the junction
// population) and decides where the static friction peak is and when the run may stop.
// Solver-independent: both solvers feed it the same way.
//
// The first macroscopic peak (docs/model.md §5, README "The static friction peak") ends the first
// macroscopic slip, the one in which the whole interface gives way: it is the highest maximum of
// Q from the first junction slip until, after every junction has slipped at least once, either
// the next maximum of Q (included) or a stick (every slipping junction repins). Earlier sticks and
// drops are precursors. No threshold on the size of a drop is used, so the peak does not depend
// on the solver tolerance and holds for drops well under 1 %. Later peaks (stick-slip cycles) are
// maxima followed by a drop of at least `min_drop` of Q.
#include <cstdint>
#include <limits>
#include <vector>

#include "solve/core/observer.hpp"

namespace asperity {

struct Peak {  // a confirmed macroscopic peak of Q and the trough that follows it
  Extremum max, min;
};

// How the first macroscopic peak was found.
enum class PeakRule : std::uint8_t {
  none,            // not found: the run ended before every junction had slipped (Q_s: highest
                   // Q after the first slip, NaN without any slip)
  all_slipped,     // closed by the first maximum of Q after every junction had slipped
  stick,           // closed by a stick after every junction had slipped
  steady_sliding,  // every junction has slipped and neither followed (overdamped glide): Q_s is
                   // the highest Q reached, the approach to steady sliding
};
const char* to_string(PeakRule r);

struct FirstPeak {
  Extremum max{0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(), true};
  PeakRule rule = PeakRule::none;
  bool found() const { return rule != PeakRule::none; }
};

class Recorder {
 public:
  // every [s]: sampling interval; keep_series: store every sample (else only the loading
  // branch, which the quadratic fit needs); min_drop: relative drop that confirms a stick-slip
  // peak after the first one; stop_at_first_peak / stop_after_cycles: stop conditions
  // (cycles < 0: none).
  Recorder(double every, bool keep_series, double min_drop, bool stop_at_first_peak, int stop_after_cycles);

  // Time of the next sample the solver must deliver.
  double next_sample_time() const { return static_cast<double>(next_index_) * every_; }
  std::int64_t next_sample_index() const { return next_index_; }
  void sample(const Sample& s);
  void extremum(const Extremum& e);
  void population(const PopulationChange& c);
  bool done() const { return done_; }
  // A sweep's per-point time limit ended the run (the solver checks it: solve/core/run_limits.hpp).
  void mark_timed_out() { done_ = timed_out_ = true; }
  bool timed_out() const { return timed_out_; }

  const std::vector<Sample>& series() const { return series_; }
  const std::vector<Sample>& loading_branch() const { return loading_; }
  // Confirmed peaks: the first macroscopic peak, then the stick-slip peaks. The first one's
  // trough is NaN until the minimum of Q after it has been seen.
  const std::vector<Peak>& peaks() const { return peaks_; }
  // The first macroscopic peak as far as the run went (also when not confirmed).
  FirstPeak first_peak() const;
  const Sample& last() const { return last_; }
  // Largest Q seen in any sample or maximum, from t = 0 (start-up ringing included).
  const Extremum& highest() const { return highest_; }
  double every() const { return every_; }

 private:
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  void first_peak_extremum(const Extremum& e);
  void confirm_first(PeakRule rule);
  void later_peak_extremum(const Extremum& e);
  void check_stop();

  double every_;
  bool keep_series_;
  double min_drop_;
  bool stop_at_first_peak_;
  int stop_after_cycles_;
  std::int64_t next_index_ = 0;
  bool done_ = false;
  bool timed_out_ = false;
  // First peak: search state.
  bool slipped_ = false;    // some junction has slipped
  bool failed_ = false;     // every junction has slipped at least once
  bool have_best_ = false;  // a maximum of Q after the first slip
  Extremum best_{};         // the highest such maximum
  bool have_best_trough_ = false;
  Extremum best_trough_{};       // lowest minimum after best_
  bool trough_pending_ = false;  // first peak confirmed, its trough not seen yet
  PeakRule rule_ = PeakRule::none;
  Extremum highest_after_slip_{0, -std::numeric_limits<double>::infinity(), 0, true};
  Extremum highest_after_failure_{0, -std::numeric_limits<double>::infinity(), 0, true};
  // Later peaks.
  bool have_candidate_ = false;
  Extremum candidate_{};  // latest maximum not yet confirmed by a drop
  std::vector<Sample> series_, loading_;
  std::vector<Peak> peaks_;
  Sample last_{};
  Extremum highest_{0, -std::numeric_limits<double>::infinity(), 0, true};
};

}  // namespace asperity
