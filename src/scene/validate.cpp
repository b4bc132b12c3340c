#include "scene/validate.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "physics/contact_law.hpp"
#include "scene/csv.hpp"
#include "surface/neighbour_grid.hpp"

namespace asperity {

using io::format_double;
using io::format_short;

namespace {

// Limits that keep every run finite in time and memory.
constexpr double kMaxSamples = 1e6;            // samples of one run (1e6: 0.3 GB resident, 0.1 GB of series.csv)
constexpr double kMaxEtaTime = 1e6;            // η · stop.time: ≤ ~3·10^5 steps forced by damping
constexpr double kMaxPeriods = 1e6;            // slider oscillations in stop.time (≥ 2·10^7 event steps)
constexpr double kMaxReferenceSteps = 1e9;     // steps of the reference solver
constexpr double kMinSlipAreaFraction = 1e-6;  // A_s/A0 at a junction's first slip
// 4.0 GB at 20,000: the compliance matrix and its inverse (N^2 doubles) and the inverse's
// single-precision copy (N^2/2 floats).
constexpr std::size_t kMaxInteractingJunctions = 20000;

// Each error names the key the user set (the first of the pair that was given).
[[noreturn]] void blame(const KeyOrigins& o, const char* a, const char* b, const std::string& msg) {
  o.fail(o.given(a) || !o.given(b) ? a : b, msg);
  throw std::logic_error("KeyOrigins::fail returned");
}

void check_resources(const Scene& s, const KeyOrigins& o) {
  // Samples are kept in memory (56 bytes each, twice while on the loading branch).
  const double intervals = s.stop.time / s.output.every;
  if (!(intervals <= kMaxSamples * (1 + 1e-12)))
    blame(o, "output.every", "stop.time",
          "too many samples: stop.time / output.every = " + format_short(intervals) + ", more than the " +
              format_short(kMaxSamples) + " a run may record (output.every must be >= stop.time * 1e-6 = " +
              format_short(s.stop.time / kMaxSamples) + " s)");
  // Damping rate η forces explicit steps shorter than ~3/η on both solvers (the reference's
  // is unstable beyond η dt = 2; the event solver's Dormand–Prince stability limit is 3.3/η).
  const double eta_time = s.model.eta * s.stop.time;
  if (!(eta_time <= kMaxEtaTime))
    blame(o, "model.eta", "stop.time",
          "too strong damping: eta * stop.time = " + format_short(eta_time) + " is more than " +
              format_short(kMaxEtaTime) + ": damping that strong needs explicit steps shorter than ~3/eta, i.e. over " +
              format_short(eta_time / 3.3) + " steps (the slider is overdamped long before: eta = " +
              format_double(s.model.eta) + " 1/s, stop.time = " + format_double(s.stop.time) + " s)");
  // Time scales: the slider oscillates at ω = sqrt((k_L + K0)/M) with K0 = Σ k_i(A0) =
  // E κ(1) Σ ℓ0_i (κ(1) = 1/((1+ν)(1−ν/2)) for both shapes); every solver needs several steps
  // per period (the event solver ~20, the reference C_t per T0 = 2π/sqrt(K0/M)).
  double sum_l0 = 0;
  for (const double a : s.experiment.junctions.area_m2) sum_l0 += initial_diameter(a);
  const double K0 = s.experiment.E * sum_l0 / ((1.0 + s.experiment.nu) * (1.0 - 0.5 * s.experiment.nu));
  const double M = s.experiment.mass_kg;
  const double periods = s.stop.time * std::sqrt((s.experiment.k_L + K0) / M) / (2.0 * M_PI);
  if (!(periods <= kMaxPeriods))
    o.fail("stop.time", "too many slider oscillations: " + format_short(periods) +
                            " periods of 2 pi sqrt(M/(k_L + K0)) in " + format_double(s.stop.time) + " s, more than " +
                            format_short(kMaxPeriods) + " (mass = " + format_double(M) + " kg, k_L = " +
                            format_double(s.experiment.k_L) + " N/m, K0 = " + format_short(K0) + " N/m)");
  if (s.solver.method == SolverMethod::reference && K0 > 0) {
    const double steps = s.stop.time * s.solver.Ct / (2.0 * M_PI * std::sqrt(M / K0));
    if (!(steps <= kMaxReferenceSteps))
      blame(o, "solver.Ct", "stop.time",
            "too many reference steps: stop.time * Ct / T0 = " + format_short(steps) + ", more than " +
                format_short(kMaxReferenceSteps) +
                " (dt = T0/Ct = " + format_short(2.0 * M_PI * std::sqrt(M / K0) / s.solver.Ct) + " s)");
  }
}

// The area law A = A0 − α_b f²/A0^p is used between A0 and the area at the first slip,
// A_s = A0 (1 − φ_s²). If a junction would lose all but a tiny part of its area before it
// slips, the law is far outside any measured range, 1 − φ_s² is lost to rounding (and is 0 in
// double beyond β ~ 1e15, where the solvers divide by zero), and its slip distance is tiny.
void check_area_law_domain(const Scene& s, const KeyOrigins& o) {
  if (s.model.alpha_b == 0 || s.experiment.junctions.size() == 0) return;
  const ContactLaw law = make_contact_law(s.experiment, s.model);
  const auto [lo, hi] =
      std::minmax_element(s.experiment.junctions.area_m2.begin(), s.experiment.junctions.area_m2.end());
  for (const double A0 : {*lo, *hi}) {  // φ_s is monotonic in A0
    const double phi = law.slip_phi(A0);
    const double kept = sheared_area_phi(1.0, phi);  // A/A0 at the first slip
    if (kept >= kMinSlipAreaFraction) continue;
    // Blame a model key the user gave: one set by --set or a sweep (no file mark) first.
    std::string key;
    for (const char* k : {"model.p", "model.alpha_b", "model.epsilon"})
      if (key.empty() && o.given(k) && o.overridden(k)) key = k;
    for (const char* k : {"model.p", "model.alpha_b", "model.epsilon"})
      if (key.empty() && o.given(k)) key = k;
    const std::string msg =
        "junctions of " + format_short(A0) + " m^2 would keep only " + (kept > 0 ? format_short(kept) : "nothing") +
        " of their area at their first slip (A = A0 - alpha_b f^2/A0^p with p = " + format_double(s.model.p) +
        ", alpha_b = " + format_double(s.model.alpha_b) + ", sigma = sigma_exp/epsilon = " + format_short(law.sigma) +
        " Pa; at least " + format_short(kMinSlipAreaFraction) + " is needed for the law to be meaningful)";
    if (!key.empty()) o.fail(key, msg);
    // Neither key set in the scene: the experiment (areas, sigma_exp) is what is out of range.
    throw io::InputError(s.experiment.junctions_file.string(), 0, "area_m2", msg);
  }
}

// Elastic interactions (docs/model.md §8): the junctions need finite, non-overlapping positions
// (each a disc of its initial area) and a dense N × N compliance
// that fits in memory.
void check_interactions(const Scene& s, const KeyOrigins& o) {
  if (s.model.interactions == Interactions::none) return;
  const JunctionPopulation& J = s.experiment.junctions;
  const std::string csv = s.experiment.junctions_file.string();
  if (J.x_m.size() != J.size() || J.y_m.size() != J.size())
    o.fail("model.interactions",
           "elastic interactions need the junction positions: " + (csv.empty() ? std::string("the junctions") : csv) +
               " has no x_m and y_m columns");
  if (J.size() > kMaxInteractingJunctions)
    o.fail("model.interactions",
           "elastic interactions keep an N x N compliance matrix (N^2 doubles, 4 GB at 20,000): N = " +
               std::to_string(J.size()) + " junctions, more than " + std::to_string(kMaxInteractingJunctions));
  for (std::size_t i = 0; i < J.size(); ++i) {
    if (!std::isfinite(J.x_m[i]) || !std::isfinite(J.y_m[i]))
      throw io::InputError(csv, 0, "x_m", "junction " + std::to_string(i + 1) + " has a non-finite position");
    // The positions the run uses stay within the CSV reader's bound (finite squared distances).
    const double reach = std::max(std::abs(J.x_m[i]), std::abs(J.y_m[i]));
    if (reach > kMaxJunctionCoordinate_m)
      throw io::InputError(csv, 0, "x_m",
                           "junction " + std::to_string(i + 1) + " is centred " + format_short(reach) +
                               " m away; centres must be within +-" + format_short(kMaxJunctionCoordinate_m) + " m");
    if (reach * s.model.position_scale > kMaxJunctionCoordinate_m)
      o.fail("model.position_scale", "junction " + std::to_string(i + 1) + " of " + csv + " would be centred " +
                                         format_short(reach * s.model.position_scale) +
                                         " m away; centres must be within +-" + format_short(kMaxJunctionCoordinate_m) +
                                         " m");
  }
  if (s.model.position_scale != 1.0) {  // the positions the run uses: a scale below 1 may overlap
    JunctionPopulation scaled = J;
    for (double& v : scaled.x_m) v *= s.model.position_scale;
    for (double& v : scaled.y_m) v *= s.model.position_scale;
    if (const auto pair = first_overlap(scaled))
      o.fail("model.position_scale", "junctions " + std::to_string(pair->first + 1) + " and " +
                                         std::to_string(pair->second + 1) + " of " + csv + " overlap at scale " +
                                         format_short(s.model.position_scale));
  }
  if (const auto pair = first_overlap(J)) {
    const auto [i, j] = *pair;
    const std::string msg = "junctions " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                            " overlap (centres " + format_short(std::hypot(J.x_m[i] - J.x_m[j], J.y_m[i] - J.y_m[j])) +
                            " m apart, radii sqrt(A0/pi) = " + format_short(disc_radius(J.area_m2[i])) + " and " +
                            format_short(disc_radius(J.area_m2[j])) +
                            " m); elastic interactions need separate junctions";
    if (csv.empty() && o.given("experiment.junctions")) o.fail("experiment.junctions", msg);  // inline
    if (csv.empty()) throw io::InputError("", 0, "x_m", msg);
    // The CSV's row of the second junction (read again: only on this error path).
    std::vector<int> lines;
    try {
      (void)read_junctions_csv(s.experiment.junctions_file, csv, lines);
    } catch (const std::exception&) {  // changed since it was read: no line then
      lines.clear();
    }
    throw io::InputError(csv, j < lines.size() ? lines[j] : 0, "x_m", msg);
  }
}

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> first_overlap(const JunctionPopulation& J) {
  // Cells of the largest diameter: a pair that overlaps lies in neighbouring cells, so each
  // junction is compared with the 3 x 3 cells around it (O(N) for even sizes).
  const std::size_t n = J.size();
  if (n < 2) return std::nullopt;
  double r_max = 0, extent = 0;
  for (const double A : J.area_m2) r_max = std::max(r_max, disc_radius(A));
  for (std::size_t i = 0; i < n; ++i) extent = std::max({extent, std::abs(J.x_m[i]), std::abs(J.y_m[i])});
  NeighbourGrid grid(2 * r_max, extent);
  for (std::size_t i = 0; i < n; ++i) grid.insert(i, J.x_m[i], J.y_m[i]);
  for (std::size_t i = 0; i < n; ++i) {
    std::optional<std::pair<std::size_t, std::size_t>> pair;
    grid.for_each_near(J.x_m[i], J.y_m[i], 1, [&](std::size_t j) {
      if (j <= i) return true;
      const double d = std::hypot(J.x_m[i] - J.x_m[j], J.y_m[i] - J.y_m[j]);
      if (d < disc_radius(J.area_m2[i]) + disc_radius(J.area_m2[j])) pair = std::pair{i, j};
      return !pair;
    });
    if (pair) return pair;
  }
  return std::nullopt;
}

void validate_scene(const Scene& s, const KeyOrigins& origins) {
  check_resources(s, origins);
  check_area_law_domain(s, origins);
  check_interactions(s, origins);
}

}  // namespace asperity
