#pragma once
// The verdicts of the interaction study (interaction_study.hpp) as pure functions of what
// its runs measured: each model's A(Q) against the measured curve at its noise, per load and over
// the loads, and what the joint calibrations match. interaction_study.cpp runs the models and fills
// the rows; interaction_report.cpp writes them and these verdicts.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "observe/shape_comparison.hpp"
#include "studies/claim_verdicts.hpp"    // AreaComparison
#include "studies/joint_comparison.hpp"  // JointFitEntry, ForceMisfit

namespace asperity::interaction_detail {

// ---- Each model at its own calibrated α_b (the paper's method, per load) ----

struct Side {  // one model on one experiment
  bool ran = false;
  double alpha_b = NAN;
  Observables obs;
  AreaComparison areas;
  ShapeComparison shape;  // against the measured curve at its noise (no measured curve: NaN)
  double wall_s = 0;
};

// One experiment: the independent and the interacting model, each at its own calibrated α_b.
struct StudyRow {
  std::string name;
  Side indep, inter;
};

// The verdict's counts over the loads (see verdict_of).
struct Tally {
  int ran = 0, quadratic = 0, indep_quadratic = 0, closer = 0, farther = 0, undecided = 0;
  double dn_sum = 0;
  int dn_count = 0;
};

// The verdict, on a measure whose spread over the measurement noise is known: the
// rms residual of each model's A(Q) at the measured points, in linear space. A model
// reproduces the measured (quadratic) shape at a load when its residual is within what noise
// alone leaves in 95 % of the bootstrap resamples; interacting is closer than independent when
// their residuals differ by more than twice the spread of the difference (the two sds added).
Tally tally_rows(const std::vector<StudyRow>& rows);

// The verdict line of the tally ("Quadratic within the noise at every load ...").
std::string verdict_of(const Tally& t);

// ---- The joint calibrations of (α_b, ε, η) against A(Q) and Q(t) ----

// One model at its joint calibration on one load: the fit's best run done again (the fit file's
// scene with its forced settings: to the last measured time, no stop at the peak or after cycles).
struct JointSide {
  bool ran = false;
  std::string missing = "no joint calibration";  // why not, when !ran
  JointFitEntry fit;
  Observables obs;
  ForceMisfit force;
  ShapeComparison shape;
  double objective = NAN;  // the re-run's area_and_force term (the fit's objective, again)
  double wall_s = 0;
};

// One load: both models at their joint calibrations.
struct JointRow {
  std::string name;
  JointSide indep, inter;
};

// Whether a model's re-run at its joint calibration matches the measured Q(t), the measured A(Q),
// within the noise.
bool q_within(const JointSide& s);
bool a_within(const JointSide& s);

// Which of the two models passes `pass` at one load: "independent", "interacting", "both",
// "neither"; a model without a joint run reads "no evidence" for its part.
template <class Pass>
std::string which_pass(const JointRow& r, Pass pass) {
  if (!r.indep.ran && !r.inter.ran) return "no evidence";
  if (r.indep.ran && r.inter.ran) {
    const bool a = pass(r.indep), b = pass(r.inter);
    return a && b ? "both" : a ? "independent" : b ? "interacting" : "neither";
  }
  const bool only_indep = r.indep.ran;
  const bool p = pass(only_indep ? r.indep : r.inter);
  return std::string(only_indep ? "independent: " : "interacting: ") + (p ? "yes" : "no") + " (" +
         (only_indep ? "interacting" : "independent") + ": no evidence)";
}

// The loads whose re-run of each model matches Q(t) and A(Q), out of those that ran.
struct JointTally {
  int indep_ran = 0, inter_ran = 0, indep_q = 0, inter_q = 0, indep_a = 0, inter_a = 0;
};
JointTally tally_joint(const std::vector<JointRow>& rows);

// The verdict's paragraph on the joint calibrations (`loads`: the study's loads).
std::string joint_verdict(const JointTally& t, std::size_t loads);

}  // namespace asperity::interaction_detail
