#pragma once
// Resource limits of one run: stop.wall_time, stop.max_slips and a sweep's per-point
// time_limit. Checked inside the solver loops (every step or event), so that no input can keep
// a run going unseen; a solver that reaches one stops cleanly and says which (RunInfo).
#include <chrono>
#include <cstdint>
#include <limits>
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

// Counts calls and looks at the clock every 64th (a clock read costs ~20 ns, a solver step
// 0.1–10 µs), so the check is free in the loops and a limit is seen within microseconds.
class LimitGuard {
 public:
  explicit LimitGuard(const RunLimits& limits)
      : max_slips_(limits.max_slips),
        deadline_(limits.wall_time_s < 1e9
                      ? std::chrono::steady_clock::now() +
                            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(limits.wall_time_s))
                      : std::chrono::steady_clock::time_point::max()) {}

  LimitHit check(std::int64_t slips) {
    if (slips >= max_slips_) return LimitHit::max_slips;
    if ((++calls_ & 63) == 0 && std::chrono::steady_clock::now() >= deadline_) return LimitHit::wall_time;
    return LimitHit::none;
  }

 private:
  std::int64_t max_slips_;
  std::chrono::steady_clock::time_point deadline_;
  std::uint64_t calls_ = 0;
};

// One line for a run stopped by `hit` at simulated time t_end with `slips` slips, naming the
// scene key, e.g. "stop.wall_time: run stopped after 3600 s of wall time at simulated t =
// 0.0123 s of 10 s (raise stop.wall_time...)". For max_slips it names the smallest slip
// distance of the population, the usual cause.
std::string limit_message(const Scene& scene, const RunLimits& limits, LimitHit hit, double t_end,
                          std::int64_t slips);

}  // namespace asperity
