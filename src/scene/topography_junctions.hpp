#pragma once
// Junctions from topography: the recipe's surface with its sphere, the frictionless
// normal contact (surface/normal_contact.hpp), its clusters (surface/segmentation.hpp) merged
// until their equivalent discs are disjoint, and the experiment they make. Same recipe, same
// numbers (the thread count does not change them).
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.hpp"
#include "scene/topography_recipe.hpp"
#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"

namespace asperity {

// The recipe's surface, without the sphere. InputError on a bad measured map.
HeightMap topography_surface(const TopographyRecipe& recipe);

// Makes the equivalent discs (radius sqrt(A/π) at the centroid) of a population disjoint, which
// the interaction model needs (scene/validate.hpp first_overlap): while two discs overlap, the
// first such pair found is replaced by one junction of their summed area at their area-weighted
// centroid (the contact area is conserved; a merged disc may then overlap a third, which is
// merged in turn). Deterministic; the result is sorted by area, largest first (ties by x, then
// y). Returns the number of merges. O(N log N) for discs of similar sizes (a grid of cells and
// the set of discs that may still overlap: only the discs a merge changed are looked at again);
// std::length_error past `max_work` disc comparisons, which bounds the phase on a map whose
// clusters are many and overlap a few large discs.
inline constexpr std::uint64_t kMaxMergeWork = 2'000'000'000;
std::size_t merge_overlapping_junctions(JunctionPopulation& junctions, std::uint64_t max_work = kMaxMergeWork);

// What the contact solve gives: depends on the surface, R, E, ν, P and the contact settings only
// (the slider and the name do not enter), so one solve serves every scene that shares them.
struct TopographyContact {
  JunctionPopulation junctions;  // merged, x_m, y_m from the grid's centre
  std::size_t n = 0;             // the map: pixels per side and pixel size
  double pixel_m = 0;
  std::string heights_sha256;              // of the surface heights (float64 LE, row-major, before the sphere)
  double rms_height_m = 0, rms_slope = 0;  // of the surface before the sphere
  int iterations = 0;
  double residual = 0;
  double contact_area_m2 = 0;  // pixels in contact × pixel area (= Σ junction areas)
  std::size_t clusters = 0, merges = 0;
};

// Surface → sphere → contact → clusters → merged junctions. InputError when the contact solve
// does not converge within max_iterations, reaches the map's edge, or makes a junction that a
// junctions file could not hold (scene/csv.hpp's rules: generate writes one). `threads`: the contact
// solve's FFTW and loop threads (the numbers do not depend on it). `normal`, when given, receives
// the normal solve itself (pressures and gaps per pixel: the contact map the tangential solve
// takes).
TopographyContact solve_topography_contact(const TopographyRecipe& recipe, int threads = 1,
                                           NormalContact* normal = nullptr);
// The same from a surface given as heights (without the sphere, which the recipe's radius adds):
// the recipe's sphere, elastomer, load and contact settings apply, its surface keys do not.
TopographyContact solve_surface_contact(HeightMap surface, const TopographyRecipe& recipe, int threads = 1,
                                        NormalContact* normal = nullptr);

// The experiment of a recipe and its contact: name, slider, E, ν, σ_exp, junctions; the
// description says where it came from (`made_by`, e.g. "Written by `asperity generate` from x.yaml").
Experiment topography_experiment(const TopographyRecipe& recipe, const TopographyContact& contact,
                                 const std::string& made_by);

// made_by of a scene's experiment: "Made by the scene from topo.yaml when it was read." (or from
// its topography section, when inline).
std::string scene_made_by(const TopographyRecipe& recipe);

// The provenance text of the surface ("generated from a synthetic surface: self-affine ...").
std::string topography_surface_text(const TopographyRecipe& recipe);

}  // namespace asperity
