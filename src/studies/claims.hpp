#pragma once
// Evidence for the paper's claims (docs/model.md §6) on a set of experiments: from the base runs,
// the variants (studies/claim_variants.hpp) and the calibration, the REPORT.md that states,
// claim by claim, what was measured and whether it reproduces.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "report/paper_figures.hpp"
#include "scene/scene.hpp"
#include "studies/claim_variants.hpp"
#include "studies/claim_verdicts.hpp"

namespace asperity {

// α_b calibrated per experiment (the paper's quadratic_alpha), when a calibration was asked for.
struct CalibratedRun {
  std::string experiment;
  std::string failure;          // non-empty: the calibration of this experiment failed (fields below unset)
  double alpha_b = 0;           // m^(2p+2)/N²
  Observables obs;              // run at the calibrated α_b
  std::vector<Sample> loading;  // its loading branch
  int evaluations = 0;
  std::string stop_reason;  // NLopt's
};

struct Calibration {
  std::string fit_file;             // empty: no calibration asked for
  std::vector<CalibratedRun> runs;  // one per experiment of the fit, failed ones included
};

// The observables the verdicts read (studies/claim_verdicts.hpp), from the runs of this reproduction.
// Least-squares slope dA/dQ [m²/N] over Q ∈ [0, frac·Q_max] (incipient loading).
double initial_slope(std::span<const double> Q, std::span<const double> A, double frac);
// Area decay, incipient slope (Q ≤ 0.3 Q_max) and shape exponent of a run's loading branch next
// to the scene's measured curve.
AreaComparison compare_areas(const Scene& scene, double alpha_b, const Observables& o,
                             const std::vector<Sample>& loading);

ClaimObservables claim_observables(const std::vector<PaperRun>& base, const std::vector<VariantRun>& variants,
                                   const Calibration& calibration);

// REPORT.md text. `base`: the runs at the scene settings (smallest load first).
std::string claims_report(const std::vector<PaperRun>& base, const std::vector<VariantRun>& variants,
                          const Calibration& calibration, const std::string& data_label);

}  // namespace asperity
