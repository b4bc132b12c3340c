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

// DIR/savings.csv and DIR/savings.png (bar chart of the first scene; skipped without gnuplot),
// the figure drawn from the numbers as the CSV holds them (read back: read_savings_csv), so that
// redraw_savings draws it again byte for byte.
void write_savings(const std::filesystem::path& dir, const std::vector<SavingRow>& rows,
                   const FigureFormats& figures = {});

// The CSV text of the rows (header + one line per row): DIR/savings.csv.
std::string savings_csv(const std::vector<SavingRow>& rows);

// The rows of a savings.csv, numbers to its printed precision; stand_in, which the CSV does not
// hold, is false. `lines`, when given, receives each row's 1-based line. A missing file or
// column, or a field that is not a number (yes/no for baseline): InputError "FILE:LINE:COL:
// COLUMN: message".
std::vector<SavingRow> read_savings_csv(const std::filesystem::path& csv, std::vector<int>* lines = nullptr);

// `asperity bench savings --redraw`: DIR/savings.png (and its .gp, in `figures`) drawn again from
// DIR/savings.csv as write_savings drew it; nothing else is written. The stand-in mark as
// run_savings sets it, from the experiment of each of `scenes` (the ones the bench ran); a row of
// another experiment is an InputError at its line. Returns false when gnuplot did not draw (the
// reason in `*error`).
bool redraw_savings(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& scenes,
                    const FigureFormats& figures = {}, std::string* error = nullptr);

}  // namespace asperity
