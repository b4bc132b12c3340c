#pragma once
// `asperity study studies/recovery.yaml`: the recovery matrix (docs/calibration.md, "The recovery matrix").
// Synthetic experiments made by each model at a known truth (generate/synthetic.hpp; one recipe
// per load and generating model), each fitted by each model from that model's fit template with
// the same optimizer budget. Per cell: the objective J, the reduced chi-square, the parameters
// against the truth, the convergence verdict. The joint method can tell the models apart at a
// load only where the diagonal wins on both rows (decide_row). SYNTHETIC data: every file says so.
#include <cstddef>
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace asperity {

// One fitting model: its label in the matrix, its model.interactions value, its fit template
// (a fit file without `experiments`, which the study adds per synthetic experiment).
struct RecoveryModel {
  std::string label;         // "independent", "interacting"
  std::string interactions;  // "none", "elastic"
  std::filesystem::path fit_template;
};

struct RecoveryMatrixOptions {
  // The inputs and the output folder come from a study file (studies/study_load.hpp).
  std::vector<std::filesystem::path> recipes;  // synthetic recipes, one per load and generating model
  std::vector<RecoveryModel> models;           // the fitting models
  std::filesystem::path out;
  std::filesystem::path study_file;  // the study file these options came from (provenance; may be empty)
  int threads = 2;
  std::ostream* log = nullptr;
};

struct RecoveryParameter {
  std::string key;  // model.alpha_b, ...
  double value = std::numeric_limits<double>::quiet_NaN();
  double sigma = std::numeric_limits<double>::quiet_NaN();  // Hessian's, NaN where none
  double truth = std::numeric_limits<double>::quiet_NaN();  // the generating scene's value
};

// One cell: the data of `data_model` at `load`, fitted by `fit_model`.
struct RecoveryCell {
  std::string load;  // the base experiment's name (recovery-light, ...)
  double mass_kg = 0;
  int junctions = 0;
  std::string data_model, fit_model;
  std::string status = "ok";                                             // "ok" or why the fit failed
  double objective = std::numeric_limits<double>::quiet_NaN();           // J at the fit
  double objective_at_truth = std::numeric_limits<double>::quiet_NaN();  // diagonal cells only
  int residuals = 0, free_parameters = 0;
  std::string converged;  // yes / no / unverified
  int in_best_basin = 0, starts = 0, evaluations = 0;
  double wall_s = 0;
  std::vector<RecoveryParameter> parameters;
  double reduced_chi2() const {
    return residuals > free_parameters ? objective / (residuals - free_parameters)
                                       : std::numeric_limits<double>::quiet_NaN();
  }
  bool certified() const { return status == "ok" && converged == "yes"; }
};

// One row of the matrix (one data set): does the model that made the data fit it better?
// diagonal_wins when J_off − J_diag exceeds twice the standard deviation of a chi-square with the
// diagonal's residual count N, 2·sqrt(2N) (the scatter of J that the noise alone makes);
// off_diagonal_wins for the converse; undecided between; no_evidence when either fit failed or
// was not certified (a J not shown to be a minimum compares nothing).
enum class RowDecision { diagonal_wins, off_diagonal_wins, undecided, no_evidence };
const char* row_decision_name(RowDecision d);
RowDecision decide_row(const RecoveryCell& diagonal, const RecoveryCell& off_diagonal);

// Per load: "tells the models apart" when every row's diagonal wins, "no evidence" when a row has
// none (or a cell is missing), else "cannot tell them apart".
struct LoadVerdict {
  std::string load;
  double mass_kg = 0;
  std::vector<std::string> rows;  // per data model: "data_model: decision"
  std::string verdict;
};
std::vector<LoadVerdict> judge_loads(const std::vector<RecoveryCell>& cells);

// Runs the matrix and writes OUT/matrix.csv, OUT/REPORT.md, OUT/data/<load>_<model>/ (the
// synthetic experiments) and OUT/fits/ (each cell's fit file, to rerun it with `asperity fit`).
// Throws InputError for bad recipes or templates, or templates whose budgets differ.
std::vector<RecoveryCell> run_recovery_matrix(const RecoveryMatrixOptions& opt);

// matrix.csv as written above; no file: no cells. Throws InputError at a bad line and column.
std::vector<RecoveryCell> read_recovery_matrix(const std::filesystem::path& file);

// The matrix as markdown tables with the per-load verdict (REPORT.md and the interaction study's).
void write_recovery_matrix_md(std::ostream& md, const std::vector<RecoveryCell>& cells);

}  // namespace asperity
