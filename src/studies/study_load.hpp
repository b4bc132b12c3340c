#pragma once
// A study file (studies/*.yaml): which study, and every input and output path it reads or writes,
// as campaigns and fits have theirs. The study's library code holds no path of results/.
//
//   study: interactions | recovery | continuum     # required: the kind, and so the keys below
//   description: "..."                             # optional
//   out: ../results/interactions                   # required: the folder the study writes
//   threads: 2                                     # optional (1 to 1024)
// interactions (studies/interaction_study.hpp):
//   scenes: [../scenes/paper/P0.98N.yaml, ...]     # required, each a file
//   calibrations: {independent: F, interacting: F} # required: the fit.yaml of each α_b calibration
//   joint: {independent: [F...], interacting: [F...]}  # optional; absent files: no evidence
//   sweep: STORE   topography: TABLE.csv   recovery: MATRIX.csv   # optional; absent: no evidence
//   spread_experiment: P4.00N                      # optional (default P4.00N)
// recovery (studies/recovery_matrix.hpp):
//   recipes: [R.yaml, ...]                         # required, each a file
//   models:                                        # required: the fitting models, each with its template
//     - {label: independent, interactions: none, fit: FIT.yaml}
// continuum (studies/continuum_comparison.hpp):
//   recipe: RECIPE.yaml                            # required, a file
//   loads_N: [0.02, 0.1, ...]                      # required, each in [1e-6, 1e6] N
//   points: 32                                     # optional (2 to 10000)
// Relative paths are read against the study file's folder and kept lexically normal, so that a
// study run from the repository root names its files as the repository does.
#include <filesystem>
#include <string>
#include <variant>

#include "studies/continuum_comparison.hpp"
#include "studies/interaction_study.hpp"
#include "studies/recovery_matrix.hpp"

namespace asperity {

struct StudySpec {
  std::filesystem::path file;
  std::string kind;  // interactions, recovery, continuum
  std::string description;
  std::variant<InteractionStudyOptions, RecoveryMatrixOptions, ContinuumStudyOptions> options;
};

// Reads and checks a study file; every problem is an InputError naming the file, line and key.
StudySpec load_study(const std::filesystem::path& yaml);

}  // namespace asperity
