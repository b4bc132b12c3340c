#include "observe/recorder.hpp"

#include <cmath>

namespace asperity {

Recorder::Recorder(double every, bool keep_series, double min_drop, bool stop_at_first_peak,
                   int stop_after_cycles)
    : every_(every),
      keep_series_(keep_series),
      min_drop_(min_drop),
      stop_at_first_peak_(stop_at_first_peak),
      stop_after_cycles_(stop_after_cycles) {}

void Recorder::sample(const Sample& s) {
  ++next_index_;
  last_ = s;
  if (keep_series_) series_.push_back(s);
  if (peaks_.empty()) loading_.push_back(s);
  if (s.Q > highest_.Q) highest_ = {s.t, s.Q, s.A, true};
}

void Recorder::extremum(const Extremum& e) {
  if (e.Q > highest_.Q && e.is_max) highest_ = e;
  if (e.is_max) {
    // A new maximum replaces an unconfirmed lower one (a precursor that did not drop enough).
    if (!have_candidate_ || e.Q >= candidate_.Q) candidate_ = e;
    have_candidate_ = true;
    return;
  }
  if (!have_candidate_) return;
  if (candidate_.Q - e.Q >= min_drop_ * std::abs(candidate_.Q)) {
    peaks_.push_back({candidate_, e});
    have_candidate_ = false;
    // Loading branch ends at the first peak: drop samples recorded after it.
    if (peaks_.size() == 1)
      while (!loading_.empty() && loading_.back().t > candidate_.t) loading_.pop_back();
    if (stop_at_first_peak_) done_ = true;
    // n cycles = n drops with their periods: needs n + 1 peaks.
    if (stop_after_cycles_ >= 0 && static_cast<int>(peaks_.size()) >= stop_after_cycles_ + 1)
      done_ = true;
  }
}

}  // namespace asperity
