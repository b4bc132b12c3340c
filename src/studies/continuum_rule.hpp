#pragma once
// When do interactions matter? The rule the continuum study (studies/continuum.yaml) measures (docs/continuum.md):
// the independent model's error in the initial tangential stiffness against the continuum, as a
// power law of the junction population's stiffness ratio, fitted over the study's loads.
// `asperity run` applies it to a scene whose junctions have positions.
#include <cstddef>
#include <optional>
#include <vector>

namespace asperity {

// Two properties of a junction population alone (no sphere, no map), with R_app = √2 R_g the
// radius of the uniformly covered disc of the same radius of gyration (R_g² = Σ A_i |r_i − r̄|² /
// Σ A_i about the area-weighted centroid r̄; a disc of radius a has R_g² = a²/2):
//  - coverage Σ A_i / (π R_app²);
//  - stiffness ratio Σ a_i / R_app (a_i = √(A_i/π)): the junctions' summed Mindlin stiffness over
//    that of the apparent disc as one punch. Were the junctions in series with the apparent
//    contact, the independent model's stiffness error would be this ratio itself.
// NaN for fewer than two junctions or junctions without positions.
struct PopulationMeasures {
  double coverage = 0, stiffness_ratio = 0;
};
PopulationMeasures population_measures(const std::vector<double>& area_m2, const std::vector<double>& x_m,
                                       const std::vector<double>& y_m);

// |stiffness error| = prefactor · ratio^exponent (ratio: the stiffness ratio), least squares in log–log.
struct StiffnessRule {
  double prefactor = 0, exponent = 0;
  double ratio_min = 0, ratio_max = 0;  // the stiffness ratios it was fitted over
  std::size_t points = 0;
  double error_at(double ratio) const;   // the estimated |relative error|
  double ratio_for(double error) const;  // the stiffness ratio at which it reaches `error`
};

// Fits the rule to (ratio, |error|) pairs; nothing for fewer than two or a non-positive value.
std::optional<StiffnessRule> fit_stiffness_rule(const std::vector<double>& ratio, const std::vector<double>& abs_error);

// The rule of the committed study (results/continuum/rule.csv, SYNTHETIC surfaces); a test refits
// it from results/continuum/table.csv and checks these numbers.
StiffnessRule independent_stiffness_rule();

}  // namespace asperity
