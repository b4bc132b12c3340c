#pragma once
// `asperity bench accuracy`: is the default tolerance accurate enough? Each paper scene (six
// stand-ins) at its own (default) tolerance through the first peak and five stick-slip cycles,
// against a converged run (tolerance 1e-12): relative errors of Q_s, A_s, t_peak, alpha
// (target < 1e-4) and of the mean stick-slip drop and period (target < 1e-2).
#include <array>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/robust_error.hpp"
#include "observe/observables.hpp"

namespace asperity {

struct AccuracyOptions {
  std::vector<std::filesystem::path> scenes;  // default: scenes/paper/*.yaml
  // 10 s: the heaviest stand-in (P6.40N) completes its fifth cycle at 8.04 s.
  std::vector<std::string> overrides{"stop.time=10", "stop.cycles=5"};
  double converged_tolerance = 1e-12;
  std::vector<double> tolerances;  // tested tolerances; empty: each scene's own (the default)
  std::ostream* log = nullptr;
  // After each run (converged or tested): runs done and their total; may be empty.
  std::function<void(std::size_t done, std::size_t total)> on_run;
};

struct AccuracyRow {
  std::string experiment;
  double tolerance = 0;  // the tested tolerance (default: the scene's own)
  double wall_s = 0, converged_wall_s = 0;
  int cycles = 0, converged_cycles = 0;
  std::array<double, n_robust> value{}, converged{}, error{};
  bool within_targets() const;  // every error below robust_targets() (NaN fails)
};

// Errors of `run` against `converged` as one row.
AccuracyRow accuracy_row(const std::string& experiment, double tolerance, const Observables& run,
                         const Observables& converged);

std::vector<AccuracyRow> run_accuracy(const AccuracyOptions& opt);

std::string accuracy_csv(const std::vector<AccuracyRow>& rows);

// DIR/accuracy.csv.
void write_accuracy(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows);

}  // namespace asperity
