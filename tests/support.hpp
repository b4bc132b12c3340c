#pragma once
// Scenes built in code for solver tests (the paper's apparatus and defaults).
#include <vector>

#include "observe/recorder.hpp"
#include "scene/scene.hpp"
#include "solve/integrate.hpp"

namespace asperity::testing {

inline Scene paper_scene(std::vector<double> areas, double mass = 0.408) {
  Scene s;
  auto& e = s.experiment;
  e.name = "test";
  e.mass_kg = mass;
  e.k_L = 9200;
  e.v = 1e-4;
  e.E = 1.6e6;
  e.nu = 0.5;
  e.sigma_exp = 0.23e6;
  e.junctions.area_m2 = std::move(areas);
  s.stop.time = 1.0;
  s.output.every = 1e-3;
  return s;
}

// paper_scene with junction centres [m] and elastic interactions, run by `method`.
inline Scene interacting_scene(std::vector<double> areas, std::vector<double> x, std::vector<double> y,
                               SolverMethod method) {
  Scene s = paper_scene(std::move(areas));
  s.experiment.junctions.x_m = std::move(x);
  s.experiment.junctions.y_m = std::move(y);
  s.model.interactions = Interactions::elastic;
  s.solver.method = method;
  return s;
}

// Deterministic spread of areas on [lo, hi] (log-uniform, no RNG).
inline std::vector<double> spread_areas(std::size_t n, double lo, double hi) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i)
    a[i] = lo * std::pow(hi / lo, (static_cast<double>(i) + 0.5) / static_cast<double>(n));
  return a;
}

struct Outcome {
  RunInfo info;
  Recorder rec;
};

inline Outcome run(const Scene& s, bool keep_series = true) {
  Recorder rec(s.output.every, keep_series, s.output.peak_min_drop, s.stop.at_first_peak, s.stop.cycles);
  RunInfo info = integrate(s, rec);
  return {info, std::move(rec)};
}

}  // namespace asperity::testing

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace asperity::testing {
// The whole text of a file (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Writes `text` to `p` byte for byte, making its parent folders; returns `p`.
inline std::filesystem::path write_text(const std::filesystem::path& p, const std::string& text) {
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// A path in the temporary folder unique to this process (test suites may run side by side).
inline std::filesystem::path temp_path(const std::string& stem, const std::string& ext = "") {
  std::string name = stem;
  name += '-';
  name += std::to_string(::getpid());
  name += ext;
  return std::filesystem::temp_directory_path() / name;
}

// An empty folder temp_path(stem) (removed first if a crashed run left it).
inline std::filesystem::path fresh_dir(const std::string& stem) {
  const std::filesystem::path d = temp_path(stem);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}
}  // namespace asperity::testing
