#pragma once
// Scene and experiment files → typed, validated structs (scene.hpp), and back to text.
// The only code that knows YAML. Loading never writes anything.
//
// Every bad input throws InputError (input_error.hpp) with a one-line what():
//   scenes/x.yaml:7: model.epsilon: must be in (0, 1], got 1.5
//   --set model.eta=abc: model.eta: expected a number in SI units (1/s), got 'abc'
//   data/x/junctions.csv:12:1: area_m2: junction area must be > 0, got -1e-08
//
// Scene YAML (only `experiment` is required; the rest defaults to the struct defaults, which are
// the paper's values):
//   experiment: ../../data/standin/P4.00N/experiment.yaml     # relative to the scene file
//   # or: experiment: {file: ../x/experiment.yaml, mass: 0.2, k_L: 9400, E: 1.7e6, ...}
//   #     (overridable: name, description, mass, k_L, v, E, nu, sigma_exp)
//   # or, given whole (Scene.from_dict; the scene text of such a scene):
//   #   experiment: {name: x, mass: 0.2, k_L: 9400, v: 1e-4, E: 1.7e6, nu: 0.5, sigma_exp: 0.4e6,
//   #                junctions: {area_m2: [...], x_m: [...], y_m: [...]},   # x_m, y_m optional
//   #                measured: {Q_N: [...], A_m2: [...]}}                   # optional
//   #   each value checked as a row of the junctions or measured CSV is
//   # or, instead of experiment, junctions from topography (topography_recipe.hpp,
//   # docs/topography.md): the contact clusters of a rough sphere, solved when the scene is read:
//   #   topography: path/to/topo.yaml          # a recipe file, relative to the scene
//   #   topography: {recipe: topo.yaml, self_affine: {hurst: 0.6}}   # the file, some values replaced
//   #   topography: {self_affine: {...}, sphere_radius_m: 0.065, E: 1.6e6, nu: 0.5, load_N: 0.98,
//   #                contact: {...}, slider: {...}, name: x}       # a recipe inline, its surface lifted
//   model:  {eta: 100, epsilon: 0.9, c_min: 0.01, p: 1.5, alpha_b: 0.725e-15,
//            junction_shape: elliptic|circular, area_law: until_first_slip|always,
//            interactions: none|elastic, interaction_cutoff: 0, interaction_weighting: uniform|rigid,
//            position_scale: 1}
//   solver: {method: event|reference, Ct: 1e4, tolerance: 1e-9, interaction_tolerance: 1e-8}
//   stop:   {time: 1.0, at_first_peak: false, cycles: -1,
//            wall_time: 3600, max_slips: 0}   # limits per run; max_slips 0: 10^6 + 10^4 N max(1, time/s)
//   output: {every: 1e-3, series: [t, X, V, Q, A, n_slipping, n_intact], peak_min_drop: 0.02}
//
// Experiment YAML: name, mass [kg], k_L [N/m], v [m/s], E [Pa], nu, sigma_exp [Pa],
// junctions (CSV path relative to the experiment file), optional measured (CSV), optional
// description (free text). Numbers are plain SI numbers ("1.6e6", never "1.6 MPa").
//
// Keys, units and ranges: scene_keys.hpp (one table). Bounds that keep every run finite (each
// refused with file:line: key; the cross-key ones in validate.hpp, also for typed variants): solver.tolerance ≥ 1e-14;
// stop.time/output.every ≤ 1e6 samples; model.eta·stop.time ≤ 1e6; ≤ 1e6 slider periods
// 2π sqrt(M/(k_L+K0)) in stop.time; ≤ 1e9 reference steps; solver.Ct ≥ 1; model.p ≤ 10; junction
// areas in [1e-20, 1] m²; every junction keeps ≥ 1e-6 of its area at its first slip. Input files
// must be regular files of at most 16 MiB (YAML) or 256 MiB (CSV) (io::read_input_file).
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/yaml_util.hpp"  // yaml_quoted
#include "scene/csv.hpp"
#include "scene/scene.hpp"
#include "scene/typed_scene.hpp"

namespace asperity {

class TopographyCache;

// Reads an experiment file and its CSVs. `overrides` (optional) is a map of experiment values
// that replace the file's (same keys as the scene's experiment map; `file` is ignored).
Experiment load_experiment(const std::filesystem::path& yaml, const YAML::Node* overrides = nullptr);

// Reads a scene, applies `overrides` ("dotted.key=value", value parsed as YAML, e.g.
// "model.eta=50", "output.series=[t,Q,A]", "experiment=../other.yaml", "experiment.mass=0.2")
// to the tree in order, then validates. Paths in overrides are relative to the scene file.
// Setting a section (e.g. "model={eta: 50}") replaces the whole section. An error or warning about
// an override names it as "LABEL KEY=VALUE" (the command line's "--set"; Python's "overrides:").
Scene load_scene(const std::filesystem::path& yaml, const std::vector<std::string>& overrides = {},
                 const std::string& override_label = "--set");

// --- Building scenes from modified trees (sweeps, fits) -----------------------------------
// The parsed scene file (parse errors → InputError). Keep it and derive variants from it.
YAML::Node load_scene_tree(const std::filesystem::path& yaml);

// A copy of `scene_tree` with `dotted_key` set to `value` (missing maps are created; setting
// experiment.X when `experiment` is a path turns it into {file: path, X: value}). The input tree
// is not modified, and unchanged nodes keep their file lines for error messages. `value` is
// deep-copied. Key syntax errors or setting inside a non-map → InputError. Unknown keys are
// reported by scene_from_tree. Not thread-safe on a shared tree: build variants on one thread.
YAML::Node apply_override(YAML::Node scene_tree, const std::string& dotted_key, const YAML::Node& value);

// Validates and converts a scene tree. Relative paths resolve against origin_file's folder;
// errors name origin_file, the key, and the line when the node came from that file.
// `topography` (optional): where a topography scene gets its contact solve (nullptr: solved now).
Scene scene_from_tree(const YAML::Node& tree, const std::filesystem::path& origin_file,
                      TopographyCache* topography = nullptr);

// A scene given in memory (the Python module's Scene.from_dict and Scene.from_yaml): `tree` as a
// scene file's, checked by the same code; relative paths resolve against base_dir; errors name
// `display` (the tree has no lines). Scene::file stays empty. Its experiment may be given whole,
// data inline (above; also allowed in a scene file).
Scene scene_from_memory(const YAML::Node& tree, const std::filesystem::path& base_dir, const std::string& display);

// scene_from_tree, kept with where each key came from, so that variants with numbers changed
// are built and checked without the tree (typed_scene.hpp). The tree is not kept.
TypedScene typed_scene_from_tree(const YAML::Node& tree, const std::filesystem::path& origin_file,
                                 std::shared_ptr<TopographyCache> topography = nullptr);

// --- Writing --------------------------------------------------------------------------------
// The fully resolved scene: experiment as a map {file: <absolute path>, name, description and
// every scalar}, every model/solver/stop/output value. Numbers are written as the shortest text
// that reads back bit-identical, so load_scene of this text saved anywhere reproduces the same
// Scene (except Scene::file and experiment_ref, which then name the new file and the absolute
// path), provided the experiment file and its CSVs are unchanged.
std::string scene_to_yaml(const Scene& scene);

// An experiment file for `e` whose CSVs are at the given paths (relative to the experiment file;
// measured_rel empty: no measured curve). Numbers round-trip exactly.
std::string experiment_to_yaml(const Experiment& e, const std::string& junctions_rel, const std::string& measured_rel);

// The model: and solver: sections of a scene, exactly as scene_to_yaml writes them.
std::string model_solver_yaml(const ModelSettings& m, const SolverSettings& solver);

}  // namespace asperity
