#pragma once
// The robust observables of one run (docs/model.md §4-§6), computed from what the Recorder kept and
// what the solver reported. Plain data; src/report writes it as summary.yaml.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "observe/recorder.hpp"
#include "scene/scene.hpp"
#include "solve/core/run_info.hpp"

namespace asperity {

struct Observables {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  // Initial state.
  std::size_t N = 0;  // junctions
  double A0 = nan;    // m², Σ A0_i
  double K0 = nan;    // N/m, Σ k_i(t = 0)
  double T0 = nan;    // s
  double dt = nan;    // s, T0 / C_t
  // Static friction peak (end of the loading branch).
  double Q_s = nan;                     // N
  double A_s = nan;                     // m², A at the peak
  double t_peak = nan;                  // s
  bool peak_found = false;              // the contact failed (peak_rule ≠ none); else Q_s is the highest Q
                                        // after the first slip (NaN without a slip)
  PeakRule peak_rule = PeakRule::none;  // how the peak was found (recorder.hpp)
  // Shape of A(Q) on the loading branch.
  double alpha = nan;     // m²/N², A ≈ A0 − α Q² (A0 fixed)
  double alpha_R2 = nan;  // R² of that fit
  std::size_t alpha_points = 0;
  double shape_exponent = nan;      // n of A0 − A = c Qⁿ (1: quasi-linear, 2: quadratic)
  double shape_prefactor = nan;     // c [m²/Nⁿ]
  double area_drop_fraction = nan;  // 1 − A_s/A0
  // The same fits of the experiment's measured A(Q), when it has one (A0 fixed at Σ A0_i, as
  // the paper does); NaN otherwise. The paper calibrates α_b so that alpha = alpha_measured.
  double alpha_measured = nan;
  double alpha_measured_R2 = nan;
  double shape_exponent_measured = nan;
  // Stick-slip over the first cycles (stick_slip_stats, n = 5).
  int ss_cycles = 0;
  double ss_drop = nan;     // N, mean Q_max − Q_min
  double ss_period = nan;   // s, mean time between peaks
  std::size_t n_peaks = 0;  // confirmed peaks
  // Claim 7.
  double max_f_over_sigmaA = nan;
  double max_f_over_sigma_exp_A = nan;
  // Run.
  double t_end = nan;  // s
  std::int64_t steps = 0, rejected = 0, force_evals = 0, slips = 0, repins = 0;
  double wall_s = nan;  // s, wall-clock time of the integration
};

// The fields of Observables in one table, in the order every writer lists them (summary.yaml,
// a sweep store's points.csv, fitted.csv, the bench output). Each writer picks its number format.
enum class ObservableKind {
  real,   // a double (NaN when not found)
  count,  // a whole number
  flag,   // true / false
  label,  // a name (peak_rule)
};

struct ObservableField {
  const char* name;
  const char* unit;  // SI unit; "" when dimensionless or not a number
  ObservableKind kind;
  double (*value)(const Observables&);       // real, count (exact below 2^53), flag (0/1)
  const char* (*label)(const Observables&);  // label only
  bool per_point;                            // a column of a sweep store's points.csv (peak_rule and wall_s are not)
};

const std::vector<ObservableField>& observable_fields();
const ObservableField& observable_field(const std::string& name);  // std::invalid_argument if none

// The field's value as text: reals through `real`, counts as integers, flags as true/false,
// labels as their name.
std::string observable_text(const ObservableField& f, const Observables& o, std::string (*real)(double));

// ss_cycles_max: how many stick-slip cycles to average (default 5).
Observables summarize(const Scene& scene, const RunInfo& info, const Recorder& rec, double wall_s,
                      int ss_cycles_max = 5);

}  // namespace asperity
