#pragma once
// The expected wall time of one run on one core, before running it: what a campaign's shards
// are balanced by (campaign/shard_plan.hpp). An estimate from the problem's size alone — the
// junction count N, the simulated time and the solver — with constants measured on this
// project's benchmarks (run_cost.cpp says which). It need only rank runs within a factor of a
// few: a shard's points mix many runs, and a wrong constant shifts every point of its kind alike.
#include "solve/core/problem.hpp"

namespace asperity {

// Seconds on one core, > 0, for the whole run to stop.time (a run that stops at its first peak
// or after some cycles costs less; its estimate stays the whole-run one, an upper bound):
//   independent event solver    ∝ N · t_stop            (events ∝ slips ∝ N per unit time)
//   independent reference       ∝ N · t_stop / dt       (one pass over the junctions per step)
//   interacting event solver    ∝ (N² + c N) · t_stop   (fitted to `bench interacting`'s first-peak
//                                                        rows: N slips, each a few passes over the
//                                                        shrinking pinned block, plus O(N) work)
//   interacting reference       ∝ N³ · t_stop / dt      (a dense solve per step)
// plus a fixed cost per run (scene, observables, one row).
double expected_run_seconds(const Problem& problem);

}  // namespace asperity
