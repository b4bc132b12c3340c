#pragma once
// Scenes for benchmarks: a scene file plus `--set`-style overrides, validated like `asperity run`.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

// load_scene(path, overrides), with a clear InputError when the file is missing (bench commands
// default to paths relative to the repository root).
Scene bench_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides);

// "key=value" with value printed exactly (shortest round-trip text).
std::string set_number(const std::string& key, double value);

// The six paper scenes scenes/paper/P*.yaml under `dir`, sorted by name.
std::vector<std::filesystem::path> paper_scenes(const std::filesystem::path& dir);

}  // namespace asperity
