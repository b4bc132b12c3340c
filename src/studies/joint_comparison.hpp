#pragma once
// The joint calibrations of (α_b, ε, η) (objective area_and_force) in the interaction
// study: each model re-run at its calibrated values per load, its Q(t) against the measured
// Q(t) at that curve's noise, its A(Q) against the measured A(Q) by the study's residual rule.
//  - force_misfit: the rms of Q_model(t_k) − Q_k over the measured samples, the noise level
//    σ = noise_relative · max_k Q_k (the fit's own unit of a force residual), the rms that noise
//    alone leaves in 95 % of cases (σ sqrt(χ²_{n,0.95}/n)), and the rms's own spread over that
//    noise (to say whether two models differ);
//  - read_joint_fits: the calibrated values, their intervals and χ² parts from a fit.yaml of
//    `asperity fit` (a missing file or load: no entry, the study says "no evidence").
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "scene/csv.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

struct ForceMisfit {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  int n = 0;               // measured samples compared
  double rms = nan;        // N, rms of Q_model(t_k) − Q_k
  double rms_sd = nan;     // N, its standard deviation over the measurement noise (rms_spread)
  double noise = nan;      // N, σ = noise_relative · max_k Q_k
  double noise_p95 = nan;  // N, the rms noise alone leaves in 95 % of cases (noise_rms_p95)
  bool within_noise() const { return rms <= noise_p95; }
};

// 95th percentile of the rms of n independent Gaussian values of standard deviation sd:
// sd · sqrt(q/n), q the 0.95 quantile of χ² with n degrees of freedom (Boost.Math).
double noise_rms_p95(double sd, int n);

// Standard deviation of R = sqrt(mean_k (d_k + e_k)²) over Gaussian e_k of sd σ, d fixed, to
// first order: Var(R²) = (4σ² mean(d²) + 2σ⁴)/n, sd(R) = sqrt(Var(R²)) / (2R), with mean(d²)
// estimated as max(R² − σ², 0). At d = 0: σ / sqrt(2n).
double rms_spread(double rms, double sd, int n);

// The model's Q(t) (its series, linearly interpolated at the measured times as the fit does:
// fit/objective.hpp model_force_at) against the measured Q(t) with noise noise_relative · max Q.
ForceMisfit force_misfit(const std::vector<Sample>& series, const MeasuredForce& measured, double noise_relative);

// One load's joint calibration as fit.yaml states it.
struct JointParameter {
  double value = ForceMisfit::nan, sigma = ForceMisfit::nan, lo95 = ForceMisfit::nan, hi95 = ForceMisfit::nan,
         profile_sigma = ForceMisfit::nan;
  bool at_bound = false;
};
struct JointFitEntry {
  std::string label;
  std::string status;                                // "ok", or "failed" (then `failure` says why; no values to use)
  std::string failure;                               // the fit's failure, or its uncertainty's (Hessian) failure
  std::filesystem::path fit_yaml;                    // where it was read
  std::filesystem::path fit_file;                    // the fit file it names (fit_file:), as written
  std::map<std::string, JointParameter> parameters;  // by scene key (model.alpha_b, ...)
  double objective = ForceMisfit::nan, reduced_chi2 = ForceMisfit::nan;
  double chi2_area = ForceMisfit::nan, chi2_force = ForceMisfit::nan;
  int n_area = 0, n_force = 0;
  int n_residuals = 0;    // every residual of the objective (A(Q), Q(t), cycle features)
  std::string converged;  // fit.yaml's: yes, no, unverified ("" from an older file)
  int in_best_basin = 0, starts = 0;
};

// label → entry for every fit in the files, in order: the first fit of status ok of a label is
// kept; a failed one only while no file has an ok one. Absent files are skipped. A file that is
// not a fit.yaml: InputError.
std::map<std::string, JointFitEntry> read_joint_fits(const std::vector<std::filesystem::path>& fit_yamls);

}  // namespace asperity
