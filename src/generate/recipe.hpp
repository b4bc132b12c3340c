#pragma once
// The stand-in recipe (data/standin/recipe.yaml): everything `asperity generate` needs to
// rebuild the six stand-in experiments byte for byte (docs/model.md §7). Plain data + a strict
// reader (unknown keys, wrong types and bad values are InputError "FILE:LINE: KEY: message").
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "generate/distributions.hpp"
#include "scene/scene.hpp"

namespace asperity {

struct StandinRecipe {
  std::filesystem::path file;  // where it was read from (provenance)

  // Seeds. Per experiment i (0-based, in the order of masses_kg):
  //   area seed  = splitmix64(seed + i)          (junction areas, then positions)
  //   noise seed = splitmix64(area seed ^ 0x6e6f697365)   ("noise": measured-curve noise)
  std::uint64_t seed = 0;

  // Experiments (docs/model.md §2).
  double gravity = 9.81;          // m/s², P = M g
  std::vector<double> masses_kg;  // slider masses M, one experiment each
  double k_L = 9200.0;            // N/m
  double v = 1.0e-4;              // m/s
  double E = 1.6e6;               // Pa
  double nu = 0.5;
  double sigma_exp = 0.23e6;  // Pa

  // Junctions: N = round(junctions_per_newton · P), areas from `distribution`.
  double junctions_per_newton = 300.0;
  Distribution distribution;
  double square_side_m = 0.0;  // > 0: also draw positions uniform in [0, L]² (L recorded)
  // > 0: junction centres in an apparent contact disc (generate/positions.hpp) of radius
  // contact_radius_m · (P / contact_reference_load_N)^(1/3) (Hertz: a ∝ P^(1/3)), from the
  // positions seed; exclusive with square_side_m.
  double contact_radius_m = 0.0;
  double contact_reference_load_N = 4.0;

  // Stand-in measured curve A = A0 − α_exp Q² (+ noise) for Q ∈ [0, Q_s(model)].
  double alpha_b = 0.725e-15;     // m⁵/N², model run that gives Q_s
  double drop_smallest = 0.15;    // (A0 − A)/A0 at Q_s, smallest load
  double drop_largest = 0.25;     // ... largest load (linear in P in between)
  int points = 60;                // samples, Q equally spaced from 0 to Q_s
  double noise_relative = 0.002;  // std of the Gaussian noise on A, in units of A0

  // Stand-in "measured" Q(t) (optional section measured_force): the model's own Q(t) at the
  // paper parameters and alpha_b above, from t = 0 to t_peak · (1 + force_after_peak), sampled
  // every force_every, plus Gaussian noise of force_noise_relative · Q_s from the force seed
  // splitmix64(area seed ^ 0x666f726365) ("force"). force_every = 0: no Q(t) files.
  double force_every = 0.0;       // s
  double force_after_peak = 0.5;  // window beyond the peak, as a fraction of t_peak
  double force_noise_relative = 0.002;

  // The model run that gives Q_s (paper parameters otherwise; stops at the first peak).
  SolverSettings solver;
  double run_stop_time = 10.0;  // s, hard end when no peak is confirmed
  double run_every = 1e-3;      // s
  double run_peak_min_drop = 1e-3;

  // Scenes written with --scenes (scenes/paper/P*.yaml).
  double scene_stop_time = 10.0;  // s
  double scene_every = 1e-3;      // s
};

std::uint64_t experiment_seed(const StandinRecipe& r, std::size_t i);
std::uint64_t noise_seed(std::uint64_t experiment_seed);
// splitmix64(area seed XOR 0x706f736974696f6e ("position")): the stream of the junction centres.
std::uint64_t positions_seed(std::uint64_t experiment_seed);
// splitmix64(area seed XOR 0x666f726365 ("force")): the noise of the stand-in Q(t).
std::uint64_t force_seed(std::uint64_t experiment_seed);

// Reads and validates a recipe. Throws InputError.
StandinRecipe load_recipe(const std::filesystem::path& path);

}  // namespace asperity
