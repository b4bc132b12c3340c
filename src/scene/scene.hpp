#pragma once
// Typed, validated description of one run. Plain data: only src/scene/*.cpp knows YAML.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "physics/contact_law.hpp"
#include "physics/elastic_interaction.hpp"
#include "scene/topography_recipe.hpp"

namespace asperity {

// Junction centres lie within ±this many metres (as read and as scaled by model.position_scale):
// distances squared stay finite in the interaction kernel, and no contact is kilometres wide
// (the far-apart limit in the tests puts junctions 1e7 m apart).
inline constexpr double kMaxJunctionCoordinate_m = 1e9;

// Junctions of one interface, as segmented from an image (or drawn by the generator).
struct JunctionPopulation {
  std::vector<double> area_m2;   // initial areas A0_i > 0
  std::vector<double> x_m, y_m;  // optional centre positions (empty when absent)
  std::size_t size() const { return area_m2.size(); }
};

// Measured A(Q) samples of an experiment (optional).
struct MeasuredCurve {
  std::vector<double> Q_N, A_m2;
};

struct Experiment {
  std::string name;
  std::filesystem::path file;            // the experiment YAML (for provenance)
  std::filesystem::path junctions_file;  // resolved CSV path
  std::filesystem::path measured_file;   // resolved CSV path, empty when absent
  double mass_kg = 0;                    // slider mass M
  double k_L = 0;                        // N/m, loading spring
  double v = 0;                          // m/s, driving velocity
  double E = 0;                          // Pa
  double nu = 0;
  double sigma_exp = 0;  // Pa, measured frictional shear strength
  JunctionPopulation junctions;
  std::optional<MeasuredCurve> measured;
  std::string description;  // free text from the experiment file (e.g. "stand-in data"); may be empty
};

enum class Interactions { none, elastic };

struct ModelSettings {
  double eta = 100.0;  // 1/s
  double epsilon = 0.90;
  double c_min = 0.01;
  double p = 1.5;
  double alpha_b = 0.725e-15;  // m^(2p+2)/N² (m⁵/N² for p = 1.5)
  JunctionShape junction_shape = JunctionShape::elliptic;
  AreaLaw area_law = AreaLaw::until_first_slip;
  // Tangential elastic interactions between junctions (docs/model.md §8): none (the paper's
  // independent junctions) or elastic (needs junction positions x_m, y_m).
  Interactions interactions = Interactions::none;
  double interaction_cutoff = 0;  // m; pairs farther apart are dropped; 0: every pair
  // How a junction's traction is spread over its disc in the coupling (physics/
  // elastic_interaction.hpp): uniform, or the rigid punch's (consistent with Mindlin's diagonal).
  TractionWeighting interaction_weighting = TractionWeighting::uniform;
  // Multiplies every junction centre (about the origin): the same arrangement in an apparent
  // contact s times as wide, s² times less crowded (the interaction study's axis).
  double position_scale = 1.0;
};

enum class SolverMethod { reference, event };

struct SolverSettings {
  SolverMethod method = SolverMethod::event;
  double Ct = 1e4;          // reference: dt = T0 / Ct
  double tolerance = 1e-9;  // event solver: relative local error per step
  // Event solver with interactions: each exact solve of the coupled pinned junctions stops when
  // its last correction is below this fraction of the junctions' slip forces, and slip positions
  // are located to it (docs/interactions.md, "The interaction tolerance").
  double interaction_tolerance = 1e-8;
};

struct StopSettings {
  double time = 1.0;           // s, hard end of the run
  bool at_first_peak = false;  // stop once the first macroscopic peak of Q is confirmed
  int cycles = -1;             // stop once this many stick-slip cycles are complete (-1: never)
  // Resource limits, checked inside the solver loops (solve/core/run_limits.hpp): reaching one ends
  // the run with a SolverError naming the key. The defaults never trigger on the shipped scenes.
  double wall_time = 3600.0;   // s of wall-clock time for one run
  std::int64_t max_slips = 0;  // pinned → slipping transitions; 0: automatic (default_max_slips)
};

// Names of the columns series.csv may hold, in file order.
inline const std::vector<std::string>& all_series() {
  static const std::vector<std::string> names{"t", "X", "V", "Q", "A", "n_slipping", "n_intact"};
  return names;
}

struct OutputSettings {
  double every = 1e-3;                             // s, sampling interval of series and loading-branch fit
  std::vector<std::string> series = all_series();  // empty: no series.csv
  // A Q maximum counts as a peak if Q then drops by this fraction. 2 %: the ringing of Q after
  // single slips (drops ≲ 1 %) is not stick-slip; with equal areas 1e-3 gave a 0.03 s "period"
  // (ringing) where 0.02–0.05 give the true 0.126 s.
  double peak_min_drop = 0.02;
};

struct Scene {
  std::filesystem::path file;            // the scene YAML
  std::filesystem::path experiment_ref;  // as written in the scene (relative to it)
  Experiment experiment;
  // A scene whose `topography:` section makes its experiment (topography_recipe.hpp): the
  // experiment above is then the recipe's, its junctions those of the contact solve.
  std::optional<TopographyRecipe> topography;
  ModelSettings model;
  SolverSettings solver;
  StopSettings stop;
  OutputSettings output;
};

// Contact law implied by an experiment and model settings (σ = σ_exp/ε, docs/model.md §2).
inline ContactLaw make_contact_law(const Experiment& e, const ModelSettings& m) {
  ContactLaw c;
  c.E = e.E;
  c.nu = e.nu;
  c.epsilon = m.epsilon;
  c.sigma = e.sigma_exp / m.epsilon;
  c.alpha_b = m.alpha_b;
  c.p = m.p;
  c.shape = m.junction_shape;
  return c;
}

}  // namespace asperity
