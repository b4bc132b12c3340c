#include "observe/recorder.hpp"

#include <cmath>

namespace asperity {

const char* to_string(PeakRule r) {
  switch (r) {
    case PeakRule::none:
      return "none";
    case PeakRule::stick:
      return "stick";
    case PeakRule::all_slipped:
      return "all_slipped";
    case PeakRule::steady_sliding:
      return "steady_sliding";
  }
  return "none";
}

Recorder::Recorder(double every, bool keep_series, double min_drop, bool stop_at_first_peak, int stop_after_cycles)
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
  const Extremum here{s.t, s.Q, s.A, true};
  if (s.Q > highest_.Q) highest_ = here;
  if (slipped_ && s.Q > highest_after_slip_.Q) highest_after_slip_ = here;
  if (failed_ && s.Q > highest_after_failure_.Q) highest_after_failure_ = here;
}

void Recorder::extremum(const Extremum& e) {
  if (e.is_max && e.Q > highest_.Q) highest_ = e;
  if (e.is_max && slipped_ && e.Q > highest_after_slip_.Q) highest_after_slip_ = e;
  if (peaks_.empty()) return first_peak_extremum(e);
  if (trough_pending_) {
    // Extrema alternate: the first minimum after the first peak is its trough.
    if (!e.is_max) {
      peaks_.front().min = e;
      trough_pending_ = false;
      check_stop();
    }
    return;
  }
  later_peak_extremum(e);
}

void Recorder::first_peak_extremum(const Extremum& e) {
  if (!slipped_) return;  // start-up ringing of the slider: no junction has slipped, no friction peak
  if (e.is_max) {
    if (!have_best_ || e.Q > best_.Q) {
      best_ = e;
      have_best_ = true;
      have_best_trough_ = false;
    }
    // The whole interface has slipped: this maximum is the last one of the first macroscopic slip.
    if (failed_) confirm_first(PeakRule::all_slipped);
  } else if (have_best_ && (!have_best_trough_ || e.Q < best_trough_.Q)) {
    best_trough_ = e;
    have_best_trough_ = true;
  }
}

void Recorder::population(const PopulationChange& c) {
  if (c.new_slips > 0) slipped_ = true;
  if (!peaks_.empty()) return;
  // A stick after every junction has slipped ends the first macroscopic slip; earlier sticks
  // (precursors, ringing of a weakly damped slider) do not.
  if (c.stick && failed_ && have_best_) return confirm_first(PeakRule::stick);
  if (slipped_ && c.n_intact == 0) failed_ = true;
}

void Recorder::confirm_first(PeakRule rule) {
  rule_ = rule;
  peaks_.push_back({best_, have_best_trough_ ? best_trough_ : Extremum{nan, nan, nan, false}});
  trough_pending_ = !have_best_trough_;
  // The loading branch ends at the first peak: drop samples recorded after it.
  while (!loading_.empty() && loading_.back().t > best_.t) loading_.pop_back();
  check_stop();
}

void Recorder::later_peak_extremum(const Extremum& e) {
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
    check_stop();
  }
}

void Recorder::check_stop() {
  if (peaks_.empty() || trough_pending_) return;  // the first peak's drop is part of its result
  if (stop_at_first_peak_) done_ = true;
  // n cycles = n drops with their periods: needs n + 1 peaks.
  if (stop_after_cycles_ >= 0 && static_cast<int>(peaks_.size()) >= stop_after_cycles_ + 1) done_ = true;
}

FirstPeak Recorder::first_peak() const {
  FirstPeak p;
  if (!peaks_.empty()) {
    p.max = peaks_.front().max;
    p.rule = rule_;
  } else if (failed_) {
    // Every junction slipping and no maximum since: Q approaches steady sliding.
    p.max = have_best_ && best_.Q >= highest_after_failure_.Q ? best_ : highest_after_failure_;
    p.rule = PeakRule::steady_sliding;
  } else if (slipped_ && std::isfinite(highest_after_slip_.Q)) {
    p.max = highest_after_slip_;
  }
  return p;
}

}  // namespace asperity
