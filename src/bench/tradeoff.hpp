#pragma once
// `asperity bench tradeoff`: the measured speed–accuracy trade.
//
// Work-precision study on a bench experiment the reference can finish (bench/scenes/P0.20N.yaml:
// 60 junctions drawn with the stand-in recipe, peak at 0.65 s, five stick-slip cycles by
// 0.78 s): converged solution = event solver at tolerance 1e-12 (checked against 1e-13);
// reference at several C_t and event solver at several tolerances, each with its wall time and
// the relative error of each robust observable. (The side-by-side speed on a paper scene over the
// whole run: bench/speed_ratio.hpp.)
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/robust_error.hpp"
#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

struct TradeoffOptions {
  std::filesystem::path scene = "bench/scenes/P0.20N.yaml";  // work-precision experiment
  std::vector<double> Ct{1e2, 1e3, 1e4};
  std::vector<double> tolerances{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11};
  double converged_tolerance = 1e-12;
  double check_tolerance = 1e-13;  // converged vs this: how converged the converged run is
  double stop_time = 2.0;          // s, the runs stop after peak + `cycles` cycles
  int cycles = 5;
  int repeats = 5;              // runs faster than 1 s: median of this many
  std::ostream* log = nullptr;  // progress lines
  // After each setting: settings done and their total (for a progress line); may be empty.
  std::function<void(std::size_t done, std::size_t total)> on_setting;
};

struct WorkPrecisionRow {
  std::string experiment, method;  // method: "reference" (setting = C_t) or "event" (tolerance)
  double setting = 0;
  double wall_s = 0;  // median wall time of the integration [s]
  double cpu_s = 0;   // median process CPU time of the same runs [s]
  int repeats = 1;
  double t_end = 0;  // simulated time [s]
  std::int64_t steps = 0;
  std::array<double, n_robust> value{}, error{};  // error: relative, vs the converged run
};

// Observed order of convergence of the reference between two C_t: log(e1/e2) / log(Ct2/Ct1).
struct OrderRow {
  std::string observable;
  double Ct_lo = 0, Ct_hi = 0, order = 0;
};

struct TradeoffResult {
  bool stand_in = false;               // the experiment is a stand-in (is_stand_in): the figure says so
  std::vector<WorkPrecisionRow> rows;  // converged and check runs included (method "event")
  std::vector<OrderRow> orders;
};

TradeoffResult run_tradeoff(const TradeoffOptions& opt);

// Writes DIR/work_precision.csv, DIR/reference_order.csv and
// DIR/work_precision.png (skipped when gnuplot is missing). Creates DIR. The figure is drawn from
// the rows as the CSV holds them (read back: read_work_precision_csv), so that redraw_tradeoff
// draws it again byte for byte.
void write_tradeoff(const std::filesystem::path& dir, const TradeoffResult& r, const FigureFormats& figures = {});

// The CSV text of the rows (header + one line per row).
std::string work_precision_csv(const std::vector<WorkPrecisionRow>& rows);

// The rows of a work_precision.csv, numbers to its printed precision (values exact; a value or
// error that could not be measured as nan). `lines`, when given, receives each row's 1-based
// line. A missing file or column, or a field that is not a number: InputError
// "FILE:LINE:COL: COLUMN: message".
std::vector<WorkPrecisionRow> read_work_precision_csv(const std::filesystem::path& csv,
                                                      std::vector<int>* lines = nullptr);

// `asperity bench tradeoff --redraw`: DIR/work_precision.png (and its .gp, in `figures`) drawn
// again from DIR/work_precision.csv as write_tradeoff drew it; nothing else is written. The
// stand-in mark as run_tradeoff sets it, from the experiment of `scene` (the one the bench ran);
// a row of another experiment is an InputError at its line. Returns false when gnuplot did not
// draw (the reason in `*error`).
bool redraw_tradeoff(const std::filesystem::path& dir, const std::filesystem::path& scene,
                     const FigureFormats& figures = {}, std::string* error = nullptr);

}  // namespace asperity
