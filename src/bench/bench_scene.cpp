#include "bench/bench_scene.hpp"

#include <algorithm>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "scene/load.hpp"

namespace asperity {
namespace fs = std::filesystem;

Scene bench_scene(const fs::path& path, const std::vector<std::string>& overrides) {
  if (!fs::exists(path))
    throw io::InputError(path.string(), 0, "",
                         "scene file not found (bench commands take paths relative "
                         "to the current folder: run them from the repository root or pass the path)");
  return load_scene(path, overrides);
}

std::string set_number(const std::string& key, double value) { return key + "=" + io::format_double(value); }

std::vector<fs::path> paper_scenes(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw io::InputError(dir.string(), 0, "", "scene folder not found (run from the repository root or pass --scenes)");
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".yaml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  if (out.empty()) throw io::InputError(dir.string(), 0, "", "no *.yaml scene in this folder");
  return out;
}

}  // namespace asperity
