#include "solve/core/run_cost.hpp"

#include <cmath>

namespace asperity {

namespace {
// Constants, seconds on one core, from the committed benchmarks (the runs and figures each comes
// from: docs/performance.md, "Figures behind the code's choices"):
// event: per junction·simulated second (results/bench/speed_runs.csv);
// reference: per junction·step (results/bench/speed_ratio.csv);
// interacting event: seconds per simulated second a N² + b N through the first-peak rows of
//   results/bench/interacting.csv; the test "run cost: the model is within a factor of two of
//   the committed benchmarks" holds it;
// interacting reference: one LU-like dense solve of N³/3 flops per step, ~1 Gflop/s;
// per run: loading the scene, observables and the row, ~1 ms.
constexpr double kEventPerJunctionSecond = 2.5e-5;
constexpr double kReferencePerJunctionStep = 2.6e-6;
constexpr double kInteractingEventPerSquareSecond = 1.73e-7;
constexpr double kInteractingEventPerJunctionSecond = 7.8e-5;
constexpr double kInteractingReferencePerCubeStep = 3.3e-10;
constexpr double kPerRun = 1e-3;
}  // namespace

double expected_run_seconds(const Problem& p) {
  const double n = static_cast<double>(p.size());
  const double t = std::isfinite(p.t_stop) && p.t_stop > 0 ? p.t_stop : 0.0;
  const double steps = p.dt > 0 && std::isfinite(p.dt) ? t / p.dt : 0.0;
  const bool event = p.solver.method == SolverMethod::event;
  double s = 0;
  if (p.interacting())
    s = event ? (kInteractingEventPerSquareSecond * n + kInteractingEventPerJunctionSecond) * n * t
              : kInteractingReferencePerCubeStep * n * n * n * steps;
  else
    s = event ? kEventPerJunctionSecond * n * t : kReferencePerJunctionStep * n * steps;
  return kPerRun + (std::isfinite(s) ? s : 0.0);
}

}  // namespace asperity
