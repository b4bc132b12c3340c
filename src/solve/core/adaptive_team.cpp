#include "solve/core/adaptive_team.hpp"

#include <algorithm>

namespace asperity {

namespace {
// A choice must be this much cheaper to take over (hysteresis against timing noise).
constexpr double kMargin = 1.15;
// Moving-average weight of the newest region.
constexpr double kWeight = 0.3;
// A probe that lost is repeated after at least this many times its own duration (its cost at
// most 1/20 of the time) and at least twice the last interval, but never after more than
// kLongestWait of measured time: a machine that became quiet again is seen within about that.
constexpr double kAmortise = 20;
constexpr double kLongestWait = 1.0;  // s
constexpr double kFirstWait = 0.01;   // s
// Until the loser of a switch, whose last region took `seconds`, is tried again.
double wait_for(double seconds) { return std::min(kLongestWait, std::max(kFirstWait, kAmortise * seconds)); }
}  // namespace

int AdaptiveTeam::choose(double work) {
  if (max_ == 1 || work < min_work_) return 1;
  probing_ = since_probe_s_ >= probe_after_s_;
  const bool wide = probing_ ? !wide_now_ : wide_now_;
  return wide ? max_ : 1;
}

void AdaptiveTeam::record(int threads, double seconds, double work) {
  seconds_ += seconds;
  if (max_ == 1 || work < min_work_) return;
  const int k = threads > 1 ? 1 : 0;
  (k ? wide_ : narrow_) += 1;
  last_s_[k] = seconds;
  const double c = seconds / work;
  const int now = wide_now_ ? 1 : 0;
  // A probe's estimate starts afresh (the last one may be from another load); the current
  // choice's is a moving average.
  cost_[k] = cost_[k] < 0 || probing_ ? c : (1 - kWeight) * cost_[k] + kWeight * c;
  if (probing_) {
    probing_ = false;
    since_probe_s_ = 0;
    if (cost_[k] * kMargin < cost_[now]) {
      wide_now_ = !wide_now_;  // the other choice won: take it
      probe_after_s_ = wait_for(last_s_[now]);
    } else {
      probe_after_s_ = std::min(kLongestWait, std::max({kAmortise * seconds, 2 * probe_after_s_, kFirstWait}));
    }
    return;
  }
  since_probe_s_ += seconds;
  // The current choice became dearer than the other's last estimate: switch at once.
  const int other = 1 - now;
  if (cost_[other] >= 0 && cost_[now] > kMargin * cost_[other]) {
    wide_now_ = !wide_now_;
    since_probe_s_ = 0;
    probe_after_s_ = wait_for(seconds);
  }
}

}  // namespace asperity
