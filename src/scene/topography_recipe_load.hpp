#pragma once
// Topography recipes from YAML (topography_recipe.hpp): a recipe file, or a scene's lifted
// `topography:` section. Every bad value is one InputError "FILE:LINE: KEY: message".
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "io/yaml_util.hpp"
#include "scene/topography_recipe.hpp"

namespace asperity {

// True when `path` is a YAML map with a top-level `topography` key (a topography recipe rather
// than the stand-in recipe). InputError when it cannot be read as YAML.
bool is_topography_recipe(const std::filesystem::path& path);

// Reads and validates a recipe file. Throws InputError ("FILE:LINE: KEY: message"); a measured
// map is checked to exist here, and read (and checked) by topography_surface.
TopographyRecipe load_topography_recipe(const std::filesystem::path& path);

// A scene's `topography:` map (the recipe's keys with its surface section lifted: smooth,
// self_affine or file next to sphere_radius_m, load_N, ...), checked as a recipe file is; errors
// name `src` and the keys as topography.KEY. Paths (file:) resolve against base_dir.
TopographyRecipe topography_recipe_from_scene(const io::Source& src, const YAML::Node& section,
                                              const std::filesystem::path& base_dir);

}  // namespace asperity
