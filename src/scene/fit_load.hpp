#pragma once
// Fit files (fits/*.yaml) → FitSpec (fit/fit_spec.hpp), fully validated. Every bad input throws
// InputError naming the fit file, the line and the key, e.g.
//   fits/x.yaml:12: parameters.model.alpha_b.start: must be in [lo, hi] = [1e-16, 3e-15], got 5e-15
//
// Format (SI units; paths relative to the fit file; only experiments, parameters required):
//   name: paper_alpha_b            # output folder results/fits/<name>/ (default: file stem)
//   description: "..."             # free text
//   objective: quadratic_alpha     # quadratic_alpha | area_curve | stick_slip
//   separate: true                 # one independent fit per experiment (default false: joint)
//   experiments:                   # scene files; each runs one experiment
//     - ../scenes/paper/P0.98N.yaml
//     - scene: ../scenes/paper/P1.52N.yaml
//       set: {model.eta: 50}       # fixed scene values for this experiment (dotted keys)
//       target: {drop: 0.1, period: 0.13}   # N, s: stick_slip objective only (required there)
//   parameters:                    # free parameters, by numeric scene key
//     model.alpha_b: {lo: 1e-16, hi: 3e-15, start: 0.725e-15, scale: log, per_experiment: false}
//   optimizer: {algorithm: LN_BOBYQA, xtol_rel: 1e-4, ftol_rel: 0, ftol_abs: 0,
//               max_evaluations: 60, initial_step: 0.1}
//   profile: {parameter: model.alpha_b, span: 0.2, points: 11}   # or false
//   error_bars: {experiment.E: 0.1e6, experiment.k_L: 200, ...}  # one-at-a-time ± refits
//
// Each experiment's scene is run with forced settings that the objective needs: output.series
// = [] always; stop.at_first_peak = true for quadratic_alpha and area_curve (only the loading
// branch matters); stop.at_first_peak = false and stop.cycles = 5 for stick_slip.
#include <filesystem>

#include "fit/fit_spec.hpp"
#include "scene/input_error.hpp"

namespace asperity {

FitSpec load_fit(const std::filesystem::path& fit_yaml);

// NLopt's name of an algorithm is accepted by load_fit (derivative-free, needs no subsidiary
// optimizer); "" when it is, else the reason.
std::string check_fit_algorithm(const std::string& name);

}  // namespace asperity
