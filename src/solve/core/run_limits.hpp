#pragma once
// Resource limits of one run: stop.wall_time, stop.max_slips and a sweep's per-point
// time_limit. Checked inside the solver loops (every step or event), so that no input can keep
// a run going unseen; a solver that reaches one stops cleanly and says which (RunInfo).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "scene/scene.hpp"

namespace asperity {

enum class LimitHit : std::uint8_t { none, wall_time, max_slips };

struct RunLimits {
  double wall_time_s = std::numeric_limits<double>::infinity();
  std::int64_t max_slips = std::numeric_limits<std::int64_t>::max();
};

// stop.max_slips when 0 (automatic): 10^6 + 10^4 per junction per simulated second (at least
// one second). The shipped scenes need ≲ 10^2 per junction per second (P0.98N: 25 957 slips of
// 294 junctions in 10 s); a junction that chatters (slips and repins at once, see
// limit_message) reaches it within seconds.
std::int64_t default_max_slips(const Scene& scene);

// The scene's limits (stop.wall_time, stop.max_slips or its default).
RunLimits run_limits(const Scene& scene);

// The moment `limits.wall_time_s` from now runs out (time_point::max() for none).
inline std::chrono::steady_clock::time_point wall_deadline(const RunLimits& limits) {
  if (!(limits.wall_time_s < 1e9)) return std::chrono::steady_clock::time_point::max();
  return std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                std::chrono::duration<double>(limits.wall_time_s));
}

// Counts calls and reads the clock every stride-th: the stride doubles (up to 64) while the calls
// between two reads take under a millisecond and halves (down to 1) otherwise. Fast loops (an
// independent solver step takes 0.1–10 µs, a clock read ~20 ns) read it every 64th call, so the
// check is free there; slow ones (an interacting step at N = 20,000 takes seconds) read it every
// call. A limit is seen within about a millisecond or one call, whichever is longer.
class LimitGuard {
 public:
  explicit LimitGuard(const RunLimits& limits)
      : max_slips_(limits.max_slips), deadline_(wall_deadline(limits)), last_read_(std::chrono::steady_clock::now()) {}

  std::chrono::steady_clock::time_point deadline() const { return deadline_; }

  LimitHit check(std::int64_t slips) {
    if (slips >= max_slips_) return LimitHit::max_slips;
    if (++calls_ < next_read_) return LimitHit::none;
    const auto now = std::chrono::steady_clock::now();
    const bool quick = now - last_read_ < std::chrono::milliseconds(1);
    stride_ = quick ? std::min<std::uint64_t>(2 * stride_, 64) : std::max<std::uint64_t>(stride_ / 2, 1);
    next_read_ = calls_ + stride_;
    last_read_ = now;
    return now >= deadline_ ? LimitHit::wall_time : LimitHit::none;
  }

 private:
  std::int64_t max_slips_;
  std::chrono::steady_clock::time_point deadline_, last_read_;
  std::uint64_t calls_ = 0, next_read_ = 1, stride_ = 1;
};

// Thrown from inside one long step of a solver once the wall-time deadline has passed: an
// avalanche at fixed X is one step, and at N = 20,000 interacting junctions it can hold thousands
// of slips, minutes to hours. integrate() ends the run there as its guard would between steps,
// every sample before that step kept.
class WallTimeReached : public std::runtime_error {
 public:
  WallTimeReached() : std::runtime_error("the wall-time limit was reached inside a step") {}
};

// One line for a run stopped by `hit` at simulated time t_end with `slips` slips, naming the
// scene key, e.g. "stop.wall_time: run stopped after 3600 s of wall time at simulated t =
// 0.0123 s of 10 s (raise stop.wall_time...)". For max_slips it names the smallest slip
// distance of the population, the usual cause.
std::string limit_message(const Scene& scene, const RunLimits& limits, LimitHit hit, double t_end, std::int64_t slips);

}  // namespace asperity
