#pragma once
// What to calibrate, against what, and how (plain data; src/fit/fit_load.cpp reads it from a
// fit YAML file, tests may build it in code).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "scene/csv.hpp"
#include "scene/scene_template.hpp"

namespace asperity {

enum class FitObjective {
  quadratic_alpha,  // Σ_e (α_model/α_measured − 1)²: the paper's calibration (docs/model.md §5)
  area_curve,       // Σ_e mean_j ((A_model(Q_j) − A_j)/A0)² over the measured samples
  stick_slip,       // Σ_e (drop/drop_target − 1)² + (period/period_target − 1)²
  area_and_force,   // Σ_e χ²: A(Q) and Q(t) samples and (with a target) the stick-slip drop and
                    // period, each residual in units of its noise level (FitNoise); objective.hpp
  user,             // Σ_e of the caller's own term per run (FitOptions::user_term; the Python
                    // module's callable); never read from a fit file
};

const char* objective_name(FitObjective o);

struct FitParameter {
  std::string key;              // numeric scene key (numeric_scene_keys()), e.g. model.alpha_b
  double lo = 0, hi = 0;        // bounds, SI; respected exactly
  double start = 0;             // SI, in [lo, hi]
  bool log_scale = false;       // the optimizer moves log(x) (needs lo > 0)
  bool per_experiment = false;  // one value per experiment (joint fits); else shared
};

// Stick-slip targets of one experiment (the stand-ins have no measured stick-slip).
struct StickSlipTarget {
  double drop_N = std::numeric_limits<double>::quiet_NaN();    // mean Q_max − Q_min
  double period_s = std::numeric_limits<double>::quiet_NaN();  // mean time between peaks
};

struct FitExperiment {
  std::string name;                    // label in outputs (the experiment name of the scene)
  SceneTemplate scene;                 // the scene with the fit's fixed settings applied
  StickSlipTarget target;              // stick_slip objective; optional with area_and_force
  std::optional<MeasuredForce> force;  // measured Q(t): area_and_force objective (required there)
  std::filesystem::path force_file;    // its CSV (provenance, inputs.txt)
  // Replaces the scene's measured A(Q) in every run (a bootstrap draw's synthetic data); unset:
  // the scene's own.
  std::optional<MeasuredCurve> measured_override;
  bool has_target() const { return std::isfinite(target.drop_N) && std::isfinite(target.period_s); }
};

// How an area_and_force objective scores the measured Q(t) (objective.hpp).
enum class ForceScore {
  pointwise,           // every sample against the model's Q at its instant
  loading_and_cycles,  // samples to the measured first peak pointwise; the stick-slip after it by
                       // its mean drop and period (read the same way from both curves)
  loading_and_peaks,   // the loading branch as loading_and_cycles; the peaks after it each paired
                       // by time with the model's (observe/peak_pairing.hpp)
  automatic,           // per experiment: loading_and_cycles where the measured Q(t) shows two
                       // complete stick-slip cycles or more, else pointwise (objective.hpp)
};
const char* force_score_name(ForceScore s);

// Noise levels of the area_and_force objective: each residual is divided by its level, so a
// term of n samples contributes about n at a fit within the noise (a chi-square), whatever its
// units. Relative: area to the experiment's Σ A0, force to the largest measured Q, stick-slip
// to the target drop and period.
struct FitNoise {
  double area = 0.002;       // the stand-ins' A(Q) noise (data/standin/recipe.yaml)
  double force = 0.002;      // the stand-ins' Q(t) noise
  double stick_slip = 0.05;  // drop and period known to 5 %
};

// A quantity measured with an error bar; the fit is repeated with it at nominal − bar and
// nominal + bar (one at a time) to give the range of the fitted parameters.
struct ErrorBar {
  std::string key;  // numeric scene key, e.g. experiment.E
  double bar = 0;   // absolute, SI (e.g. 0.1e6 Pa)
};

struct ProfileSettings {
  std::size_t parameter = 0;            // index into FitSpec::parameters: the first profiled one
  std::vector<std::size_t> parameters;  // every profiled parameter (empty: just `parameter`)
  double span = 0.2;                    // relative: values x*·(1 ± span)
  int points = 11;                      // ≥ 2 (odd: includes the optimum)
};

struct FitSpec {
  std::string name;                // results/fits/<name>/
  std::filesystem::path file;      // the fit file (provenance); empty for a spec given in memory
  std::filesystem::path base_dir;  // the folder its relative paths were read against
  std::string memory_text;         // a spec given in memory: its YAML (hashed into a journal's inputs)
  std::string user_objective_id;   // the caller's own objective, as a digest of its source: in a
                                   // journal's inputs, so an edited one does not resume it
  std::string description;
  FitObjective objective = FitObjective::quadratic_alpha;
  std::vector<FitParameter> parameters;
  std::vector<FitExperiment> experiments;
  bool separate = false;                // one independent fit per experiment (per-load fits)
  std::string algorithm = "LN_BOBYQA";  // NLopt name, derivative-free (LN_*/GN_*)
  double xtol_rel = 1e-4;               // on each parameter (relative to its value)
  double ftol_rel = 0;                  // on the objective; 0: off
  double ftol_abs = 0;                  // on the objective; 0: off
  int max_evaluations = 60;             // per optimization (the first stage when polishing)
  // Optional second stage: a local algorithm started from the first stage's best point (e.g.
  // GN_DIRECT_L to find the basin, then LN_BOBYQA to converge in it); "" = none. Error-bar
  // refits, which start at the optimum, run this stage alone.
  std::string polish_algorithm;
  int polish_max_evaluations = 100;
  double initial_step = 0.1;  // first step, as a fraction of each scaled box [0, 1]
  // Starts (fit/convergence.hpp): the first is the algorithm (then the polish) from `start`; each
  // further one is the local stage (the polish when there is one, else the algorithm) from a
  // point of a Sobol design. ≥ 2 starts ending in the best basin certify the optimum; one start
  // is `unverified`.
  int starts = 1;
  // A fit whose optimum no second start confirms (converged no or unverified) is a failed check:
  // `asperity fit` exits 1. false accepts an unconfirmed optimum (a point evaluation, a costly
  // one-start fit): said on stderr and in fit.yaml, exit 0.
  bool certify = true;
  double basin_tolerance = 1e-3;  // relative on the objective (BasinRule::relative)
  double basin_distance = 1e-3;   // in the scaled coordinates (BasinRule::distance)
  bool profile = true;            // write profile.csv / profile.png
  ProfileSettings profile_settings;
  std::vector<ErrorBar> error_bars;                // empty: no error-bar refits
  FitNoise noise;                                  // area_and_force only
  ForceScore force_score = ForceScore::automatic;  // area_and_force only (docs/calibration.md)
  // Statistical intervals from the curvature of the objective at the optimum (area_and_force:
  // a chi-square): central finite differences of relative step `hessian_step` per parameter,
  // covariance 2 s² H⁻¹ with s² the reduced chi-square at the optimum (fit.hpp, Uncertainty).
  bool intervals = false;  // default true for area_and_force
  double hessian_step = 0.01;
  // Parametric bootstrap at a certified optimum (area_and_force with intervals): this many
  // synthetic data sets, the model's curves at the optimum plus Gaussian noise at the levels of
  // `noise` times s, the root of the reduced chi-square (as the Hessian's covariance 2 s² H⁻¹;
  // seeded from bootstrap_seed), each refitted by the local stage from the optimum; σ
  // is the spread of their optima (fit.hpp, Bootstrap). For an objective that is not quadratic
  // on the scale of σ, where the Hessian's σ understates the scatter. 0: none.
  int bootstrap_draws = 0;
  std::uint64_t bootstrap_seed = 1;
};

}  // namespace asperity
