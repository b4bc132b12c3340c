#pragma once
// `asperity bench savings`: "model only what a scene requires". Times each
// saving against its baseline on the same scene (default: stand-in P4.00N):
//   series    full series (every column)        vs output.series=[]  (integration + writing)
//   stop      peak + 5 stick-slip cycles        vs stop.at_first_peak=true
//   area_law  alpha_b = 0.725e-15 (Eq. 3)       vs alpha_b = 0 (linear junctions, no area law)
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

struct SavingsOptions {
  std::vector<std::filesystem::path> scenes{"scenes/paper/P4.00N.yaml"};
  std::vector<std::string> overrides{"stop.time=10", "stop.cycles=5"};  // the baseline run
  int repeats = 5;                // baseline and variant run alternately, this many times each
  std::filesystem::path scratch;  // where run directories are written for timing (then removed)
  std::ostream* log = nullptr;
};

struct SavingRow {
  std::string experiment, saving, variant;  // variant: what differs from the scene's defaults
  bool baseline = false;
  bool stand_in = false;  // the scene's experiment is a stand-in (is_stand_in): the figure says so
  double wall_s = 0;      // median integration wall time [s]
  double cpu_s = 0;       // median process CPU time of the same runs [s]
  double write_s = 0;     // writing the run directory (series.csv, summary, scene) [s]
  int repeats = 1;
  double t_end = 0;  // simulated [s]
  std::int64_t steps = 0, force_evals = 0;
  std::size_t series_bytes = 0;  // memory of the recorded series
  double total_s() const { return wall_s + write_s; }
};

std::vector<SavingRow> run_savings(const SavingsOptions& opt);

// DIR/savings.csv and DIR/savings.png (bar chart of the first scene; skipped without gnuplot).
void write_savings(const std::filesystem::path& dir, const std::vector<SavingRow>& rows,
                   const FigureFormats& figures = {});

}  // namespace asperity
