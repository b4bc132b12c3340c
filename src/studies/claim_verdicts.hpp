#pragma once
// The verdict on each claim of docs/model.md §6, as pure functions of plain observables (what the
// runs of one `asperity reproduce` measured; claims.cpp fills them, tests make them up).
// Every verdict is one of three:
//   reproduced      the runs it needs exist and meet the rule;
//   not_reproduced  some run it needs contradicts the rule (one counter-example is enough);
//   no_evidence     no contradiction, but a run it needs is missing or failed, or cannot show
//                   the effect (e.g. a run stopped before its peak, no calibration).
// A claim over several loads combines them: any not_reproduced → not_reproduced, else any
// no_evidence → no_evidence, else reproduced (no loads → no_evidence).
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "observe/observables.hpp"

namespace asperity {

enum class Verdict { reproduced, not_reproduced, no_evidence };

const char* verdict_text(Verdict v);  // "Reproduced", "Not reproduced", "No evidence"
Verdict combine(std::span<const Verdict> per_load);

// The rules' thresholds (documented in README and REPORT.md).
struct ClaimRules {
  double dt_lo = 0.7e-6, dt_hi = 1.4e-6;  // claim 1: "dt ≈ 1 µs", mid loads
  double same_loading = 0.01;             // claims 3a, 4: relative difference of Q_s, A_s, t_peak, α
  double same_stick_slip = 0.05;          // claim 3a: of the mean stick-slip drop and period
  double same_c_min = 0.01;               // claim 4: of Q_s, A_s, t_peak, drop and period
  // Claim 3b: "stick-slip vanishes for η ≳ 180–200" read as a threshold in
  // [180 (1 − 10 %), 200 (1 + 10 %)] = [162, 220] 1/s; 10 %: the claim's own spread (200/180).
  double vanish_min = 162, vanish_max = 220;
  double match = 0.25;          // claim 5: |model/measured − 1| of decay and slope
  double quasi_linear_n = 1.6;  // claims 5, 8: model n below this
  double quadratic_n = 1.7;     // claim 5: measured n above this
  double quadratic_R2 = 0.999;  // claim 6
};

// Claim 5's comparison at one α_b: model against the measured curve (NaN where unknown).
struct AreaComparison {
  double alpha_b = Observables::nan;         // m^(2p+2)/N²
  double decay_model = Observables::nan;     // 1 − A_s/A0
  double decay_measured = Observables::nan;  // 1 − A_last/A0 of the measured curve
  double slope_model = Observables::nan;     // dA/dQ over Q ≤ 0.3 Q_max, m²/N
  double slope_measured = Observables::nan;
  double n_model = Observables::nan;  // exponent of A0 − A = c Qⁿ
  double n_measured = Observables::nan;
};

// One load. A variant is std::nullopt when its run is missing or failed.
struct LoadObservables {
  std::string experiment;
  Observables base;             // at the scene settings
  double base_eta = 100;        // 1/s, the base run's η
  bool past_first_peak = true;  // the runs were allowed to go on after the first peak
  std::vector<std::pair<double, std::optional<Observables>>> eta_scan;  // (η, run), η ≠ base_eta
  std::optional<Observables> c_min_low, equal_areas, circular, area_law_always;
  AreaComparison at_scene_alpha_b;           // base run
  std::optional<AreaComparison> calibrated;  // nullopt: no calibration or it failed
};

struct ClaimObservables {
  std::vector<LoadObservables> loads;    // smallest load first
  std::optional<Observables> reference;  // claim 7's reference-solver window
};

// --- claims ---------------------------------------------------------------------------------
Verdict claim1_dt(const ClaimObservables& c, const ClaimRules& r = {});
Verdict claim2_stick_slip(const LoadObservables& l);
Verdict claim2_stick_slip(const ClaimObservables& c);

struct EtaComparison {
  double loading_diff = Observables::nan;     // max relative difference, loading branch and peak
  double stick_slip_diff = Observables::nan;  // of the mean drop and period (inf: one has none)
  Verdict verdict = Verdict::no_evidence;
};
EtaComparison claim3_eta50_vs_base(const ClaimObservables& c, const ClaimRules& r = {});

// Where stick-slip vanishes at one load: above `last_with` (the largest η with stick-slip;
// −inf when none) and at or below `first_without` (the smallest larger η without; +inf when
// none). Reproduced when (last_with, first_without] meets the claim's range
// [vanish_min, vanish_max]: the η grid does not exclude a threshold there.
struct VanishBracket {
  double last_with = Observables::nan, first_without = Observables::nan;
  Verdict verdict = Verdict::no_evidence;
};
VanishBracket claim3_vanish_bracket(const LoadObservables& l, const ClaimRules& r = {});

struct MaxDifference {
  double diff = Observables::nan;
  Verdict verdict = Verdict::no_evidence;
};
MaxDifference claim4_c_min(const ClaimObservables& c, const ClaimRules& r = {});

struct Claim5Verdicts {
  Verdict decay = Verdict::no_evidence, slope = Verdict::no_evidence, shape = Verdict::no_evidence;
};
// Decay and slope need the calibrated run (no calibration → no_evidence); the shape contrast
// uses the calibrated run when there is one, else the base run.
Claim5Verdicts claim5_calibrated(const LoadObservables& l, const ClaimRules& r = {});
Claim5Verdicts claim5_calibrated(const ClaimObservables& c, const ClaimRules& r = {});

Verdict claim6_equal_areas(const LoadObservables& l, const ClaimRules& r = {});
Verdict claim7_forces(const ClaimObservables& c);
Verdict claim8_shape_robust(const LoadObservables& l, const ClaimRules& r = {});

// Relative difference |a − b|/|b| of two stick-slip statistics: 0 when neither run has
// stick-slip, +inf when only one has.
double stick_slip_difference(const Observables& a, const Observables& b);

}  // namespace asperity
