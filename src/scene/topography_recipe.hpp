#pragma once
// A topography recipe: a surface (smooth, self-affine, or a measured height map), a
// sphere, the elastomer's constants, a normal load and the contact solver's settings, plus the
// slider of the experiment it makes. Read from a recipe file (`asperity generate --recipe`) or
// from a scene's `topography:` section, where the recipe's own `topography:` map is lifted one
// level, so that its keys are scene keys (topography.self_affine.hurst, topography.load_N).
// Plain data (no YAML here: topography_recipe_load.hpp reads it); the contact solve is
// topography_junctions.hpp.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "surface/segmentation.hpp"
#include "surface/self_affine.hpp"

namespace asperity {

enum class TopographyKind { smooth, self_affine, measured };

struct TopographyRecipe {
  std::filesystem::path file;       // the recipe file it was read from; empty when given inline in a scene
  std::string name = "topography";  // the experiment's name

  TopographyKind kind = TopographyKind::smooth;
  SelfAffineSpec self_affine;      // self_affine (n, length_m from n × pixel or size_m)
  std::size_t n = 0;               // smooth: pixels per side ...
  double pixel_m = 0;              // ... and pixel size (self_affine and measured: set at load too)
  std::filesystem::path map_file;  // measured: .csv (pixel_m from the recipe) or .yaml header
  std::string display;             // where errors found after loading point: the recipe or the scene
  int topography_line = 0;         // line of the surface section, for errors found later

  double sphere_radius_m = 0;  // R of the paraboloid added to the surface (> 0)
  double E_Pa = 0, nu = 0.5;   // the elastomer; the counter-surface is rigid
  double load_N = 0;           // P
  double tolerance = 1e-10;    // normal contact: Σ|Δp|A / P between iterations
  int max_iterations = 5000;
  Connectivity connectivity = Connectivity::eight;

  // The slider of the experiment; defaults are the paper's (docs/model.md §2): M = P/g, k_L, v, σ_exp.
  double gravity = 9.81;      // m/s²
  double mass_kg = 0;         // 0: load_N / gravity
  double k_L = 9200.0;        // N/m
  double v = 1.0e-4;          // m/s
  double sigma_exp = 0.23e6;  // Pa
};

// The checks that span several keys of the surface (roll-off within the map, short cut-off of at
// least 2 pixels and below the roll-off), for recipes whose numbers a sweep set: the dotted key
// (topography.self_affine.X) and message of the first broken, or nothing.
struct RecipeProblem {
  std::string key, message;
};
std::optional<RecipeProblem> topography_recipe_problem(const TopographyRecipe& recipe);

// The range of one number of the recipe's elastomer, load and contact solve, by its key in the
// recipe ("sphere_radius_m", "E", "nu", "load_N", "contact.tolerance", "contact.max_iterations",
// "contact.connectivity"): the message when `value` lies outside it, else empty. The one place
// these ranges are written, for the recipe's loader and the Python bindings alike.
std::string topography_number_problem(const std::string& key, double value);

// The recipe as a scene's lifted `topography:` section (two-space indent under it, every value
// explicit, numbers round-trip exactly, the map file absolute): what scene.yaml repeats and what
// the contact cache hashes. `with_slider` false leaves out name and slider (not part of the solve).
std::string topography_section_yaml(const TopographyRecipe& recipe, bool with_slider = true);

}  // namespace asperity
