#pragma once
// `asperity bench speed`: reference vs event solver, side by side over the WHOLE run of a paper
// scene (first peak + five stick-slip cycles), in one process.
//
// The reference at C_t = 1e4 would take hours over the ~6 s simulated on P4.00N, so it runs the
// whole run at two coarse C_t. Its cost per step depends on the state (never-slipped junctions
// are bisected, slipped ones are linear), not on C_t, and its step count is exactly T_run/dt:
// the whole-run time at C_t = 1e4 is the coarse per-step cost × the step count at 1e4. The two
// coarse C_t (whole runs) and one early window at two C_t check that independence. Each run's
// error against a tight event run (tolerance 1e-12) is measured, so a ratio can be read at equal
// accuracy: the event solver at its loosest tolerance that is at least as accurate as the
// measured reference on every observable.
#include <array>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "bench/robust_error.hpp"

namespace asperity {

struct SpeedOptions {
  std::filesystem::path scene = "scenes/paper/P4.00N.yaml";
  double stop_time = 8.0;  // s; the runs stop after the first peak + `cycles` cycles
  int cycles = 5;
  double truth_tolerance = 1e-12;                                      // the accuracy yardstick (event solver)
  std::vector<double> event_tolerances{1e-4, 1e-5, 1e-6, 1e-7, 1e-8};  // + the scene's own
  std::vector<double> whole_run_Ct{25, 100};                           // reference over the whole run (T_run)
  double target_Ct = 1e4;                                              // the paper's C_t, extrapolated to
  double window_s = 2e-3;  // early window timed at target_Ct and at whole_run_Ct[0]
  int repeats = 5;         // runs faster than 1 s: median of this many
  std::ostream* log = nullptr;
};

struct SpeedRun {
  std::string method;  // "event" (setting = tolerance) or "reference" (setting = C_t)
  double setting = 0;
  bool whole = true;  // whole run (peak + cycles) or the early window
  double t_end = 0, wall_s = 0, cpu_s = 0;
  std::int64_t steps = 0;  // reference: time steps; event: accepted ODE steps
  int cycles = 0, repeats = 1;
  std::array<double, n_robust> error{};  // relative, vs the truth run (NaN for a window)
  double wall_per_step() const { return wall_s / static_cast<double>(steps); }
  double cpu_per_step() const { return cpu_s / static_cast<double>(steps); }
  double max_loading_error() const;     // max over Q_s, A_s, t_peak, alpha (NaN if any is)
  double max_stick_slip_error() const;  // max over ss_drop, ss_period
  // Every error ≤ the other's; an observable the other lacks (NaN, e.g. no stick-slip) counts
  // as larger than any finite error.
  bool at_least_as_accurate_as(const SpeedRun& other) const;
};

// One ratio: reference time per simulated second over event time per simulated second.
struct SpeedComparison {
  std::string comparison;     // what is compared
  std::string basis;          // "measured" or how the reference figure was obtained
  SpeedRun reference, event;  // reference.wall_s/cpu_s/steps may be extrapolated
  double ratio_wall() const;
  double ratio_cpu() const;
};

struct SpeedResult {
  std::string experiment;
  int threads = 1;                // OpenMP threads of the reference
  double dt_target = 0;           // dt at target_Ct [s]
  double T_run = 0;               // simulated time of the truth run (peak + cycles) [s]
  std::int64_t target_steps = 0;  // ceil(T_run / dt_target)
  SpeedRun truth;
  std::vector<SpeedRun> runs;  // every timed run except the truth
  std::vector<SpeedComparison> comparisons;
  // Per-step cost of the reference: whole run at whole_run_Ct[1] over whole_run_Ct[0], and the
  // early window at target_Ct over whole_run_Ct[0] (1 = independent of C_t).
  double whole_per_step_ratio = 0, window_per_step_ratio = 0;
};

SpeedResult run_speed(const SpeedOptions& opt);

// DIR/speed_ratio.csv (the comparisons) and DIR/speed_runs.csv (every run). Creates DIR.
void write_speed(const std::filesystem::path& dir, const SpeedResult& r);

std::string speed_ratio_csv(const SpeedResult& r);
std::string speed_runs_csv(const SpeedResult& r);

}  // namespace asperity
