#pragma once
// Junctions from topography, as files: `asperity generate --recipe` runs the recipe
// (scene/topography_recipe_load.hpp, scene/topography_junctions.hpp: surface, sphere, contact,
// clusters, merged junctions) and writes them as the junctions of an experiment (junctions.csv
// with a provenance header, experiment.yaml) that `asperity run` takes like any other. Same
// recipe, same bytes. A scene may name the recipe itself instead (docs/topography.md).
#include <filesystem>
#include <string>

#include "scene/scene.hpp"
#include "scene/topography_junctions.hpp"
#include "scene/topography_recipe_load.hpp"

namespace asperity {

// Everything the generator learnt, for the provenance header: the contact and its experiment.
struct TopographyJunctions : TopographyContact {
  Experiment experiment;      // name, slider, junctions (x_m, y_m from the grid's centre)
  std::string recipe_sha256;  // of the recipe file's bytes
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
