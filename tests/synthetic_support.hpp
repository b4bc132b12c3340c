#pragma once
// Base scenes and recipes for synthetic experiments (generate/synthetic.hpp): a small population
// (areas log-spread on [1e-9, 1e-7] m² plus six large ones, a peak the recorder confirms, as
// fit_support.hpp's), written as a real experiment folder with a scene, and the recipe text.
#include <filesystem>
#include <fstream>
#include <string>

#include "io/numbers.hpp"
#include "scene/csv.hpp"
#include "scene/load.hpp"
#include "support_files.hpp"
#include "support_scenes.hpp"

namespace asperity::testing {

// dir/base/{experiment.yaml, junctions.csv, scene.yaml}; positions (for the interacting model)
// on a square grid of `pitch` metres when pitch > 0. Returns the scene's path.
inline std::filesystem::path write_base_scene(const std::filesystem::path& dir, double mass, std::size_t n,
                                              double pitch = 0) {
  const std::filesystem::path base = dir / "base";
  std::filesystem::create_directories(base);
  Experiment e = paper_scene(spread_areas(n, 1e-9, 1e-7), mass).experiment;
  for (int i = 0; i < 6; ++i) e.junctions.area_m2.push_back(1e-7);
  if (pitch > 0) {
    const std::size_t total = e.junctions.area_m2.size();
    std::size_t side = 1;
    while (side * side < total) ++side;
    for (std::size_t i = 0; i < total; ++i) {
      e.junctions.x_m.push_back(pitch * static_cast<double>(i % side));
      e.junctions.y_m.push_back(pitch * static_cast<double>(i / side));
    }
  }
  e.name = "base";
  e.description = "a test population (synthetic_support.hpp)";
  write_junctions_csv(base / "junctions.csv", e.junctions);
  write_text(base / "experiment.yaml", experiment_to_yaml(e, "junctions.csv", ""));
  return write_text(base / "scene.yaml", "experiment: experiment.yaml\nstop: {time: 3}\n");
}

struct SyntheticTruth {
  double alpha_b = 0.7e-15, epsilon = 0.9, eta = 100;
  std::string interactions = "none";
};

// The recipe text: `scene` relative to the recipe, the truth set, noise on both curves.
inline std::string synthetic_recipe_text(const std::string& scene, const SyntheticTruth& t, double noise,
                                         std::uint64_t seed, double end, double every = 0.005, int points = 40) {
  const auto num = [](double x) { return io::format_double(x); };
  return "synthetic:\n"
         "  scene: " +
         scene +
         "\n"
         "  set:\n"
         "    model.alpha_b: " +
         num(t.alpha_b) +
         "\n"
         "    model.epsilon: " +
         num(t.epsilon) +
         "\n"
         "    model.eta: " +
         num(t.eta) +
         "\n"
         "    model.interactions: " +
         t.interactions +
         "\n"
         "  seed: " +
         std::to_string(seed) +
         "\n"
         "  noise: {area: " +
         num(noise) + ", force: " + num(noise) +
         "}\n"
         "  measured: {points: " +
         std::to_string(points) +
         "}\n"
         "  measured_force: {every: " +
         num(every) + ", end: " + num(end) + "}\n";
}

}  // namespace asperity::testing
