#pragma once
// `asperity bench interacting`: the fast interacting solver's cost and memory.
//  - scaling: synthetic populations of N = 300 … 5000 junctions with the stand-in P4.00N's
//    area distribution (its areas repeated), the slider mass ∝ N (same mean load per junction)
//    and centres placed as the stand-ins' (Hertz density in a contact disc of radius
//    4.5 mm · sqrt(N / 1201), same area fraction), each run through its first peak; the fitted
//    exponent of time ∝ N^b; peak resident memory against the N² doubles of C and G (one buffer).
//  - whole run: the stand-in P4.00N itself with the same positions, through the first peak and
//    five stick-slip cycles (or stop.time when it glides).
// STAND-IN data: the figures time the solver, not a property of the experiments.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

struct InteractingBenchOptions {
  std::filesystem::path scene = "scenes/paper/P4.00N.yaml";  // apparatus, model, area distribution
  std::vector<std::size_t> sizes{300, 600, 1200, 2400, 5000};
  double contact_radius_m = 4.5e-3;  // at the scene's own N
  bool whole_run = true;             // also the scene itself, peak + 5 cycles
  bool recorded = true;              // each size also with the scene's output series, side by side
  // Each size also at this solver.interaction_tolerance (the dense exact solver as it was before
  // the knob: converged solves), side by side with the scene's own setting; 0: not run.
  double converged_tolerance = 1e-12;
  std::ostream* log = nullptr;
};

struct InteractingBenchRow {
  // "first_peak" (scaling, no output series), "first_peak_series" (the same run recording the
  // scene's output series: the cost of recording), "first_peak_converged" (the same run at the
  // converged tolerance), "first_peak_double" (the same run without G's single-precision copy,
  // from N = 2,048 on, where the solver keeps one) or "whole_run"
  std::string what;
  std::size_t N = 0;
  double interaction_tolerance = 0;
  double wall_s = 0, t_end = 0, Q_s = 0, A_s = 0, t_peak = 0;
  std::int64_t steps = 0, slips = 0, repins = 0, solves = 0, iterations = 0, rank_one = 0, rebuilds = 0;
  std::int64_t samples = 0;                              // of the output series
  std::int64_t single_passes = 0, single_refreshes = 0;  // chord passes on G's single-precision copy
  long max_rss_kB = 0;  // of the whole process after this run (sizes run in increasing order)
  double bound_kB = 0;  // N² doubles
};

std::vector<InteractingBenchRow> run_interacting_bench(const InteractingBenchOptions& opt);
// The bench's population of N junctions from `base` (its areas repeated, mass ∝ N, to the
// first peak), the radius of its contact disc (contact_radius_m at the scene's own N, same area
// fraction), and the scene with its junctions placed in that disc (seeded like the stand-ins'
// recipe), elastic interactions, event solver.
Scene bench_population(const Scene& base, std::size_t N);
double population_radius(const Scene& base, std::size_t N, double contact_radius_m);
Scene with_positions(Scene s, double radius_m);
// Least-squares exponent b of wall_s ∝ N^b over the scaling rows; NaN unless they hold two
// distinct N or more.
double fitted_exponent(const std::vector<InteractingBenchRow>& rows);
// The line the bench prints about it: the exponent and its range of N, or why there is none.
std::string fitted_exponent_text(const std::vector<InteractingBenchRow>& rows);
// DIR/interacting.csv.
void write_interacting_bench(const std::filesystem::path& dir, const std::vector<InteractingBenchRow>& rows);

}  // namespace asperity

namespace asperity {

// The interacting solver's knobs for `bench tradeoff`: solver.tolerance and
// solver.interaction_tolerance (with the full kernel, the other at its default) and
// model.interaction_cutoff (at the default tolerances), each run's wall time and the relative
// error of the robust observables against the full kernel with both tolerances at 1e-12. The
// cut-off's error is a model error (pairs dropped), the tolerances' solver errors.
struct InteractingTradeoffOptions {
  std::filesystem::path scene = "scenes/paper/P0.98N.yaml";
  std::vector<std::string> overrides{"model.interactions=elastic", "stop.time=4"};
  std::vector<double> tolerances{1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::vector<double> interaction_tolerances{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10};
  std::vector<double> cutoffs_m{2.5e-4, 5e-4, 1e-3, 2e-3, 4e-3};
  double converged_tolerance = 1e-12;
  int repeats = 5;
  std::ostream* log = nullptr;
};

struct InteractingTradeoffRow {
  std::string knob;  // "converged", "tolerance", "interaction_tolerance", "cutoff"
  double tolerance = 0, interaction_tolerance = 0, cutoff_m = 0;  // cutoff 0: full kernel
  double wall_s = 0, cpu_s = 0;
  std::vector<double> value, error;  // robust observables (robust_names())
};

std::vector<InteractingTradeoffRow> run_interacting_tradeoff(const InteractingTradeoffOptions& opt);
// DIR/interacting_tradeoff.csv.
void write_interacting_tradeoff(const std::filesystem::path& dir, const std::vector<InteractingTradeoffRow>& rows);

}  // namespace asperity
