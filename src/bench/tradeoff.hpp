#pragma once
// `asperity bench tradeoff`: the measured speed–accuracy trade (issue 3, items 3–4).
//
// Work-precision study on a bench experiment the reference can finish (bench/scenes/P0.20N.yaml:
// 60 junctions drawn with the stand-in recipe, peak at 0.65 s, five stick-slip cycles by
// 0.78 s): converged solution = event solver at tolerance 1e-12 (checked against 1e-13);
// reference at several C_t and event solver at several tolerances, each with its wall time and
// the relative error of each robust observable. Plus the side-by-side speed on a paper scene
// (P4.00N): the reference timed on a short window, the event solver through peak + 5 cycles.
#include <array>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "bench/robust_error.hpp"

namespace asperity {

struct TradeoffOptions {
  std::filesystem::path scene = "bench/scenes/P0.20N.yaml";     // work-precision experiment
  std::filesystem::path ratio_scene = "scenes/paper/P4.00N.yaml";// speed ratio experiment
  std::vector<double> Ct{1e2, 1e3, 1e4};
  std::vector<double> tolerances{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11};
  double converged_tolerance = 1e-12;
  double check_tolerance = 1e-13;  // converged vs this: how converged the converged run is
  double stop_time = 2.0;          // s, both experiments stop after peak + `cycles` cycles
  double ratio_stop_time = 8.0;    // s
  int cycles = 5;
  double ref_window_s = 2e-3;      // s, simulated window of the timed reference on ratio_scene
  double ref_window_Ct = 1e4;
  int repeats = 5;                 // runs faster than 1 s: median of this many
  std::ostream* log = nullptr;     // progress lines
};

struct WorkPrecisionRow {
  std::string experiment, method;  // method: "reference" (setting = C_t) or "event" (tolerance)
  double setting = 0;
  double wall_s = 0;               // median wall time of the integration [s]
  double cpu_s = 0;                // median process CPU time of the same runs [s]
  int repeats = 1;
  double t_end = 0;                // simulated time [s]
  std::int64_t steps = 0;
  std::array<double, n_robust> value{}, error{};  // error: relative, vs the converged run
};

struct SpeedRatio {
  std::string experiment;
  double ref_Ct = 0, ref_window_s = 0, ref_wall_s = 0;
  std::int64_t ref_steps = 0;
  double ev_tolerance = 0, ev_t_end = 0, ev_wall_s = 0;
  int ev_cycles = 0;
  int threads = 1;                 // OpenMP threads available to the reference
  double ref_wall_per_sim() const { return ref_wall_s / ref_window_s; }
  double ev_wall_per_sim() const { return ev_wall_s / ev_t_end; }
  double ratio() const { return ref_wall_per_sim() / ev_wall_per_sim(); }
};

// Observed order of convergence of the reference between two C_t: log(e1/e2) / log(Ct2/Ct1).
struct OrderRow {
  std::string observable;
  double Ct_lo = 0, Ct_hi = 0, order = 0;
};

struct TradeoffResult {
  std::vector<WorkPrecisionRow> rows;  // converged and check runs included (method "event")
  std::vector<OrderRow> orders;
  SpeedRatio speed;
};

TradeoffResult run_tradeoff(const TradeoffOptions& opt);

// Writes DIR/work_precision.csv, DIR/reference_order.csv, DIR/speed_ratio.csv and
// DIR/work_precision.png (skipped when gnuplot is missing). Creates DIR.
void write_tradeoff(const std::filesystem::path& dir, const TradeoffResult& r);

// The CSV text of the rows (header + one line per row).
std::string work_precision_csv(const std::vector<WorkPrecisionRow>& rows);

}  // namespace asperity
