#pragma once
// Evidence for the paper's claims (MODEL.md §6) on a set of experiments: the variants each
// claim needs (η scan, c_min, equal areas, junction shape, area law, the reference solver),
// run in parallel, and the REPORT.md that states, claim by claim, what was measured and
// whether it reproduces.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "report/claim_verdicts.hpp"
#include "report/paper_figures.hpp"
#include "scene/scene.hpp"

namespace asperity {

struct ClaimVariant {
  std::string label;                   // e.g. "eta=180"
  std::function<void(Scene&)> apply;   // modifies a copy of the base scene
  bool all_experiments = true;         // false: on the first (smallest) experiment only
};

struct VariantRun {
  std::string experiment, label;
  Observables obs;
  std::string error;                   // non-empty when the run failed
};

// The variants MODEL.md §6 needs beyond the base runs.
std::vector<ClaimVariant> paper_claim_variants();

// Runs every variant on the base scenes (TBB, `threads` workers). Failures are recorded.
std::vector<VariantRun> run_variants(const std::vector<Scene>& base, const std::vector<ClaimVariant>& variants,
                                     int threads);

// α_b calibrated per experiment (the paper's quadratic_alpha), when a calibration was asked for.
struct CalibratedRun {
  std::string experiment;
  std::string failure;       // non-empty: the calibration of this experiment failed (fields below unset)
  double alpha_b = 0;        // m^(2p+2)/N²
  Observables obs;           // run at the calibrated α_b
  std::vector<Sample> loading;  // its loading branch
  int evaluations = 0;
  std::string stop_reason;   // NLopt's
};

struct Calibration {
  std::string fit_file;              // empty: no calibration asked for
  std::vector<CalibratedRun> runs;   // one per experiment of the fit, failed ones included
};

// The observables the verdicts read (report/claim_verdicts.hpp), from the runs of this reproduction.
ClaimObservables claim_observables(const std::vector<PaperRun>& base, const std::vector<VariantRun>& variants,
                                   const Calibration& calibration);

// REPORT.md text. `base`: the runs at the scene settings (smallest load first).
std::string claims_report(const std::vector<PaperRun>& base, const std::vector<VariantRun>& variants,
                          const Calibration& calibration, const std::string& data_label);

}  // namespace asperity
