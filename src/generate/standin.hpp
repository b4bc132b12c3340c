#pragma once
// Builds the stand-in experiments of docs/model.md §7 from a recipe: junction populations, the
// model's static friction peak Q_s, and a stand-in "measured" A(Q). Deterministic: the same
// recipe (and the same solver code) gives the same bytes.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "generate/recipe.hpp"
#include "observe/observables.hpp"
#include "scene/csv.hpp"
#include "scene/scene.hpp"

namespace asperity {

// Folder name of an experiment: "P" + P with two decimals + "N" (P0.98N, ..., P6.40N).
std::string standin_name(double P_newton);

// One generated experiment and what the generator learnt while building it.
struct StandinExperiment {
  Experiment experiment;  // name, parameters, junctions, measured curve
  double P = 0;           // N, M g
  std::uint64_t area_seed = 0, noise_seed = 0;
  double dt_Ct1e4 = 0;          // s, initial_info at C_t = 1e4 (paper parameters)
  Observables model;            // the model run that gave Q_s (recipe's solver)
  double area_drop_target = 0;  // (A0 − A)/A0 of the measured curve at Q_s
  double alpha_exp = 0;         // m²/N², A0 − α_exp Q² of the measured curve
  // Stand-in "measured" Q(t) (recipe measured_force; empty without it) and its provenance lines.
  MeasuredForce force;
  std::uint64_t force_seed = 0;
  double force_t_end = 0;  // s
  std::vector<std::string> force_header;
};

// The stand-in Q(t): the model's samples (t, Q) of `series` with t <= t_end, each Q plus
// Q_s · noise_relative · z, z standard normal from Uniform01(seed), in time order.
MeasuredForce standin_measured_force(const std::vector<Sample>& series, double t_end, double Q_s, double noise_relative,
                                     std::uint64_t seed);

// Builds experiment i of the recipe in memory (runs the model once). Throws SolverError.
StandinExperiment build_standin(const StandinRecipe& recipe, std::size_t i);

// The scene the generator runs to find Q_s: the experiment at paper parameters with the
// recipe's alpha_b and solver, stop at the first peak (or run_stop_time).
Scene generation_scene(const StandinRecipe& recipe, const Experiment& e);

// Stand-in measured curve: `points` Q values equally spaced on [0, Q_s],
// A = A0 − α_exp Q² + A0 · noise_relative · z, z standard normal from Uniform01(noise_seed).
MeasuredCurve standin_measured_curve(double A0, double Q_s, double alpha_exp, int points, double noise_relative,
                                     std::uint64_t noise_seed);

struct GenerateOptions {
  std::filesystem::path out_dir = "data/standin";
  std::filesystem::path scenes_dir;  // empty: write no scenes
  std::ostream* log = nullptr;       // progress lines (nullptr: silent)
};

// Builds every experiment of the recipe in recipe order (a progress line each on `log`, if set).
std::vector<StandinExperiment> build_standins(const StandinRecipe& recipe, std::ostream* log);

// Writes out_dir/<name>/{experiment.yaml, junctions.csv, measured.csv, and measured_Qt.csv when
// the recipe has measured_force} for every experiment, and out_dir/README.md.
void write_standin_experiments(const StandinRecipe& recipe, const std::vector<StandinExperiment>& xs,
                               const std::filesystem::path& out_dir);

// Writes scenes_dir/<name>.yaml for every experiment, naming its experiment.yaml by the path from
// `scenes_final` to `experiments_final`/<name>/ (the folders the files end up in, which differ
// from scenes_dir when it is a temporary folder published later).
void write_standin_scenes(const StandinRecipe& recipe, const std::vector<StandinExperiment>& xs,
                          const std::filesystem::path& scenes_dir, const std::filesystem::path& scenes_final,
                          const std::filesystem::path& experiments_final);

// build_standins, then write_standin_experiments into out_dir and (if scenes_dir is set)
// write_standin_scenes into scenes_dir. Returns the experiments in recipe order.
std::vector<StandinExperiment> generate_standins(const StandinRecipe& recipe, const GenerateOptions& opt);

// Text of out_dir/README.md (deterministic).
std::string standin_readme(const StandinRecipe& recipe, const std::vector<StandinExperiment>& xs);

// Text of a paper scene for one stand-in (experiment path as given, relative to the scene).
std::string standin_scene_yaml(const StandinRecipe& recipe, const StandinExperiment& x,
                               const std::string& experiment_rel);

}  // namespace asperity
