// solve/core/run_limits.hpp: LimitGuard sees a wall-time limit within about a millisecond of
// calls, however long each call takes (the count of calls is asserted, not a time).
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "solve/core/run_limits.hpp"

using asperity::LimitGuard;
using asperity::LimitHit;
using asperity::RunLimits;

namespace {

// Calls to check() until it reports a limit, each call `pause` after the last (at most `most`).
int calls_until_hit(const RunLimits& limits, std::chrono::microseconds pause, int most) {
  LimitGuard guard(limits);
  for (int k = 1; k <= most; ++k) {
    std::this_thread::sleep_for(pause);
    if (guard.check(0) != LimitHit::none) return k;
  }
  return most + 1;
}

}  // namespace

TEST_CASE("run limits: a wall-time limit is seen at the first slow call past it", "[solve][limits]") {
  RunLimits limits;
  limits.wall_time_s = 0.05;
  // Calls of 5 ms (a slow solver step): the limit falls in the 10th; a clock read every 64th call
  // (as before) saw it only at the 64th, 0.32 s in. Sleeps only overshoot, so fewer calls.
  CHECK(calls_until_hit(limits, std::chrono::milliseconds(5), 200) <= 11);
  // No limit: never reported, whatever the pace.
  CHECK(calls_until_hit(RunLimits{}, std::chrono::microseconds(0), 100000) == 100001);
  // The slip limit is exact at any pace.
  RunLimits slips;
  slips.max_slips = 3;
  LimitGuard guard(slips);
  CHECK(guard.check(2) == LimitHit::none);
  CHECK(guard.check(3) == LimitHit::max_slips);
}
