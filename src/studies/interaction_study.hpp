#pragma once
// `asperity study studies/interactions.yaml`: does elastic coupling between junctions (docs/model.md §8) make A(Q)
// quadratic? For each experiment, the independent model at its own
// calibrated α_b and the interacting model at its recalibrated α_b (the paper's method, per
// load), side by side: shape exponent n of A0 − A ∝ Qⁿ, area decay, incipient slope, stick-slip;
// the spread of f_i/(σA_i) at the first peak among junctions of equal area in crowded vs sparse
// neighbourhoods (the paper's Figure 2 argument); the crowding and cut-off sweep's table; each
// model re-run at its joint calibration of (α_b, ε, η), its Q(t) and A(Q) against the
// measured ones at their noise (studies/joint_comparison.hpp); the topography study's table of
// both models on junctions from contact mechanics (studies/topography_comparison.hpp). Every
// verdict is computed from the runs of the same command; missing inputs read "no evidence".
// STAND-IN data: the report says so.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

struct InteractionStudyOptions {
  // The inputs and the output folder come from a study file (studies/study_load.hpp).
  std::vector<std::filesystem::path> scenes;  // the experiments
  std::filesystem::path fit_independent;      // fit.yaml of each model's α_b calibration
  std::filesystem::path fit_interacting;
  // The joint calibrations of (α_b, ε, η) against A(Q) and Q(t), per model: fit.yaml files read
  // in order (a load found in an earlier file is not replaced); absent: no evidence.
  std::vector<std::filesystem::path> joint_independent;
  std::vector<std::filesystem::path> joint_interacting;
  std::filesystem::path sweep_store;  // of the crowding and cut-off sweep; absent: no evidence
  // The topography study's table (scripts/topography_study.py; SYNTHETIC surfaces): both models
  // on junctions from contact mechanics (studies/topography_comparison.hpp); absent: no evidence.
  std::filesystem::path topography_table;
  // The recovery matrix (studies/recovery_matrix.hpp; SYNTHETIC experiments): what the joint
  // method can tell apart, which the report leads with; absent: no evidence.
  std::filesystem::path recovery_matrix;
  std::filesystem::path out;
  std::filesystem::path study_file;  // the study file these options came from (provenance; may be empty)
  std::string spread_experiment = "P4.00N";
  int threads = 2;
  std::ostream* log = nullptr;
  FigureFormats figures;  // of force_spread (--figures)
};

// Runs the study and writes OUT/REPORT.md, table.csv, forces_at_peak.csv and figures. Returns
// the verdict line ("quadratic: no", ...).
std::string run_interaction_study(const InteractionStudyOptions& opt);

}  // namespace asperity
