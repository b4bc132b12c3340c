#pragma once
// Junctions from topography (issue 23): a recipe names a surface (smooth, self-affine, or a
// measured height map), a sphere, the elastic constants and a normal load; `asperity generate`
// adds the sphere to the surface, solves the frictionless normal contact (surface/
// normal_contact.hpp), segments the contact into clusters (surface/segmentation.hpp) and writes
// them as the junctions of an experiment (junctions.csv with a provenance header, experiment.yaml)
// that `asperity run` takes like any other. Same recipe, same bytes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/scene.hpp"
#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"
#include "surface/segmentation.hpp"
#include "surface/self_affine.hpp"

namespace asperity {

enum class TopographyKind { smooth, self_affine, measured };

struct TopographyRecipe {
  std::filesystem::path file;  // where it was read from (provenance: its name and SHA-256)
  std::string name = "topography";  // the experiment's name

  TopographyKind kind = TopographyKind::smooth;
  SelfAffineSpec self_affine;       // self_affine (n, length_m from n × pixel or size_m)
  std::size_t n = 0;                // smooth: pixels per side ...
  double pixel_m = 0;               // ... and pixel size (self_affine and measured: set at load too)
  std::filesystem::path map_file;   // measured: .csv (pixel_m from the recipe) or .yaml header
  int topography_line = 0;          // line of the topography section, for errors found later

  double sphere_radius_m = 0;       // R of the paraboloid added to the surface (> 0)
  double E_Pa = 0, nu = 0.5;        // the elastomer; the counter-surface is rigid
  double load_N = 0;                // P
  double tolerance = 1e-10;         // normal contact: Σ|Δp|A / P between iterations
  int max_iterations = 5000;
  Connectivity connectivity = Connectivity::eight;

  // The slider of experiment.yaml; defaults are the paper's (MODEL.md §2): M = P/g, k_L, v, σ_exp.
  double gravity = 9.81;            // m/s²
  double mass_kg = 0;               // 0: load_N / gravity
  double k_L = 9200.0;              // N/m
  double v = 1.0e-4;                // m/s
  double sigma_exp = 0.23e6;        // Pa
};

// True when `path` is a YAML map with a top-level `topography` key (a topography recipe rather
// than the stand-in recipe). InputError when it cannot be read as YAML.
bool is_topography_recipe(const std::filesystem::path& path);

// Reads and validates a recipe. Throws InputError ("FILE:LINE: KEY: message"); a measured map is
// checked to exist here, and read (and checked) by topography_surface.
TopographyRecipe load_topography_recipe(const std::filesystem::path& path);

// The recipe's surface, without the sphere. InputError on a bad measured map.
HeightMap topography_surface(const TopographyRecipe& recipe);

// Makes the equivalent discs (radius sqrt(A/π) at the centroid) of a population disjoint, which
// the interaction model needs (scene/validate.hpp first_overlap): while two discs overlap, the
// first such pair found is replaced by one junction of their summed area at their area-weighted
// centroid (the contact area is conserved; a merged disc may then overlap a third, which is
// merged in turn). Deterministic; the result is sorted by area, largest first (ties by x, then
// y). Returns the number of merges.
std::size_t merge_overlapping_junctions(JunctionPopulation& junctions);

// Everything the generator learnt, for the provenance header.
struct TopographyJunctions {
  Experiment experiment;            // name, slider, junctions (x_m, y_m from the grid's centre)
  std::string recipe_sha256;        // of the recipe file's bytes
  std::size_t n = 0;                // the map: pixels per side and pixel size
  double pixel_m = 0;
  std::string heights_sha256;       // of the surface heights (float64 LE, row-major, before the sphere)
  double rms_height_m = 0, rms_slope = 0;  // of the surface before the sphere
  int iterations = 0;
  double residual = 0;
  double contact_area_m2 = 0;       // pixels in contact × pixel area (= Σ junction areas)
  std::size_t clusters = 0, merges = 0;
};

// Runs the recipe (surface → sphere → contact → clusters → merged junctions). InputError when
// the contact solve does not converge within max_iterations.
// `threads`: the contact solve's FFTW and loop threads (the bytes do not depend on it).
TopographyJunctions build_topography_junctions(const TopographyRecipe& recipe, int threads = 1);

// The text of junctions.csv: '#' provenance lines, then area_m2,x_m,y_m (shortest round-trip
// numbers). Deterministic.
std::string topography_junctions_csv(const TopographyRecipe& recipe, const TopographyJunctions& t);

// Writes out_dir/junctions.csv and out_dir/experiment.yaml (folders made as needed).
void write_topography_experiment(const TopographyRecipe& recipe, const TopographyJunctions& t,
                                 const std::filesystem::path& out_dir);

}  // namespace asperity
