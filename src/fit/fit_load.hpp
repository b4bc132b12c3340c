#pragma once
// Fit files (fits/*.yaml) → FitSpec (fit/fit_spec.hpp), fully validated. Every bad input throws
// InputError naming the fit file, the line and the key, e.g.
//   fits/x.yaml:12: parameters.model.alpha_b.start: must be in [lo, hi] = [1e-16, 3e-15], got 5e-15
//
// Format (SI units; paths relative to the fit file; only experiments, parameters required):
//   name: paper_alpha_b            # output folder results/fits/<name>/ (default: file stem)
//   description: "..."             # free text
//   objective: quadratic_alpha     # quadratic_alpha | area_curve | stick_slip | area_and_force
//   separate: true                 # one independent fit per experiment (default false: joint)
//   experiments:                   # scene files; each runs one experiment
//     - ../scenes/paper/P0.98N.yaml
//     - scene: ../scenes/paper/P1.52N.yaml
//       set: {model.eta: 50}       # fixed scene values for this experiment (dotted keys)
//       target: {drop: 0.1, period: 0.13}   # N, s: stick_slip (required) or area_and_force (optional)
//       force: Qt.csv              # measured Q(t) (t_s, Q_N): area_and_force only (required there)
//   parameters:                    # free parameters, by numeric scene key
//     model.alpha_b: {lo: 1e-16, hi: 3e-15, start: 0.725e-15, scale: log, per_experiment: false}
//   optimizer: {algorithm: LN_BOBYQA, xtol_rel: 1e-4, ftol_rel: 0, ftol_abs: 0,
//               max_evaluations: 60, initial_step: 0.1,
//               polish: {algorithm: LN_SBPLX, max_evaluations: 100},   # optional local 2nd stage
//               starts: 1, basin_tolerance: 1e-3, basin_distance: 1e-3}  # multi-start (fit/convergence.hpp)
//   noise: {area: 0.002, force: 0.002, stick_slip: 0.05}   # area_and_force: residual units, each
//                                  # in [kNoiseMin, kNoiseMax] = [1e-12, 1e3] (below)
//   force_score: auto              # or pointwise | loading_and_cycles | loading_and_peaks; area_and_force only (objective.hpp)
//   intervals: true                # or {hessian_step: 0.01, bootstrap: 0, bootstrap_seed: 1};
//                                  # area_and_force only (default true); bootstrap: 0 or in
//                                  # [kBootstrapMin, kBootstrapMax] synthetic data sets (below)
//   profile: {parameter: model.alpha_b, span: 0.2, points: 11}   # or false; parameter: a key, a list, or all
//   error_bars: {experiment.E: 0.1e6, experiment.k_L: 200, ...}  # one-at-a-time ± refits
//
// The measured A(Q) of every experiment of a quadratic_alpha or area_curve fit must be what
// such a fit can use (else InputError at the experiment file's `measured` line):
//   - decreasing: the least-squares fit A = a − α Q² (a free) has α > 3 standard errors of α
//     (the stand-ins' 0.2 % noise leaves α at hundreds of standard errors; a curve that rises or
//     stays flat within its noise fails);
//   - anchored at Σ A0: |a / Σ A0 − 1| ≤ 10 % (a measured area in mm² instead of m² is off by
//     1e6, a neighbouring load's curve by ≥ 30 % on the stand-ins; the paper's area decay is
//     15–30 %, so a larger offset would be as large as the signal the fit calibrates to; a linear
//     A(Q) with a 30 % decay shifts a by only 5.6 %).
// Each experiment's scene is run with forced settings that the objective needs: output.series
// = [] always; stop.at_first_peak = true for quadratic_alpha and area_curve (only the loading
// branch matters); stop.at_first_peak = false and stop.cycles = 5 for stick_slip; for
// area_and_force output.series = [Q], stop.at_first_peak = false, no cycle stop, stop.time =
// the last measured time and output.every = min(the measured spacing, the scene's every).
#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fit/fit_spec.hpp"
#include "io/input_error.hpp"
#include "scene/scene.hpp"

namespace asperity {

// The range of each relative noise level. Below 1e-12 (a hundred times the finest
// solver.tolerance, 1e-14) the level is finer than the runs resolve and the residuals measure the
// solve's own error. Above 1e3 a residual of the whole scale adds 1e-6 to J: the term carries no
// weight, and far above it the squared residuals underflow to 0 (1e300 zeroes every one, a
// degenerate objective that every parameter value minimises).
inline constexpr double kNoiseMin = 1e-12;
inline constexpr double kNoiseMax = 1e3;

// The number of bootstrap draws (FitSpec::bootstrap_draws): two at least for a spread; each is a
// refit of up to the polish's budget, so a thousand is already hours of runs.
inline constexpr int kBootstrapMin = 2;
inline constexpr int kBootstrapMax = 1000;

// How the runs are scored. By default, the file's `objective`. With user_objective (the Python
// module's callable, FitOptions::user_term): FitObjective::user, the `objective` key must be
// absent (InputError naming it and `user_objective_name`), no measured curve is needed, and the
// only forced setting is output.series: every column when user_series (the caller reads the
// series), else none; the scene's own stop applies.
struct FitLoadOptions {
  bool user_objective = false;
  bool user_series = false;
  std::string user_objective_name = "a user objective";
};

// `overrides` ("KEY=VALUE", as --set) apply to every experiment's scene after the fit file's own
// `set`; each is checked on each scene first (InputError "--set KEY=VALUE: ...").
FitSpec load_fit(const std::filesystem::path& fit_yaml, const std::vector<std::string>& overrides = {},
                 const FitLoadOptions& options = {});

// A fit given in memory (the Python module's dict): `tree` as a fit file's, checked by the same
// code; scene paths relative to `base_dir`; errors name `display` (the tree has no lines).
// FitSpec::file stays empty, the name defaults to "fit", FitSpec::memory_text is the tree's YAML.
FitSpec fit_from_memory(const YAML::Node& tree, const std::filesystem::path& base_dir, const std::string& display,
                        const std::vector<std::string>& overrides = {}, const FitLoadOptions& options = {});

// optimizer.starts at most (each start costs up to a local stage's budget of model runs).
inline constexpr int kMaxFitStarts = 256;

// NLopt's name of an algorithm is accepted by load_fit (derivative-free, needs no subsidiary
// optimizer); "" when it is, else the reason.
std::string check_fit_algorithm(const std::string& name);

// The two rules above for one measured curve and the experiment's Σ A0 [m²]: "" when it is
// usable, else the reason (one line, no location).
inline constexpr double kMeasuredAlphaMinSigmas = 3.0;
inline constexpr double kMeasuredA0Tolerance = 0.10;
std::string measured_curve_problem(const MeasuredCurve& curve, double A0_sum);

}  // namespace asperity
