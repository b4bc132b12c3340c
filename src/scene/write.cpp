// Scene and experiment files as text: fixed key order, shortest round-trip numbers,
// double-quoted strings; deterministic bytes.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string_view>

#include "io/numbers.hpp"
#include "scene/load.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {

namespace {

// The data of an experiment given in memory (no file), as the loader reads them inline: the
// junctions and the measured curve as flow maps of columns, ten numbers a line.
std::string inline_data_yaml(const Experiment& e) {
  std::string y;
  auto column = [&](const char* name, const std::vector<double>& c) {
    y += std::string(y.back() == '{' ? "" : ",\n      ") + name + ": [";
    for (std::size_t i = 0; i < c.size(); ++i)
      y += (i ? (i % 10 ? ", " : ",\n        ") : "") + io::format_scene_number(c[i]);
    y += "]";
  };
  const JunctionPopulation& j = e.junctions;
  y += "  junctions: {";
  column("area_m2", j.area_m2);
  if (!j.x_m.empty()) column("x_m", j.x_m), column("y_m", j.y_m);
  y += "}\n";
  if (e.measured) {
    y += "  measured: {";
    column("Q_N", e.measured->Q_N);
    column("A_m2", e.measured->A_m2);
    y += "}\n";
  }
  return y;
}

// The rows of the key table whose section is one of `sections`, as "section:\n  leaf: value\n".
std::string sections_yaml(const Scene& s, std::initializer_list<std::string_view> sections) {
  std::string y, open;
  for (const SceneKey& k : scene_keys()) {
    const std::string sec = k.section();
    if (std::find(sections.begin(), sections.end(), sec) == sections.end()) continue;
    if (k.written && !k.written(s)) continue;
    if (sec != open) {
      if (open == "experiment" && s.experiment.file.empty()) y += inline_data_yaml(s.experiment);
      y += sec + ":\n", open = sec;
    }
    const std::string text = k.text(s);
    y += "  " + k.leaf() + ": " + (k.kind == KeyKind::text ? io::yaml_quoted(text) : text) + "\n";
  }
  if (open == "experiment" && s.experiment.file.empty()) y += inline_data_yaml(s.experiment);
  return y;
}

}  // namespace

std::string model_solver_yaml(const ModelSettings& m, const SolverSettings& solver) {
  Scene s;
  s.model = m;
  s.solver = solver;
  return sections_yaml(s, {"model", "solver"});
}

std::string scene_to_yaml(const Scene& s) {
  const std::string head = "# asperity scene, fully resolved: every value explicit, numbers round-trip exactly\n";
  // A topography scene repeats its recipe, which makes the same experiment again.
  if (s.topography)
    return head + "topography:\n" + topography_section_yaml(*s.topography) +
           sections_yaml(s, {"model", "solver", "stop", "output"});
  return head + sections_yaml(s, {"experiment", "model", "solver", "stop", "output"});
}

std::string experiment_to_yaml(const Experiment& e, const std::string& junctions_rel, const std::string& measured_rel) {
  if (junctions_rel.empty()) throw std::invalid_argument("experiment_to_yaml: junctions_rel must not be empty");
  std::string y;
  y += "name: " + io::yaml_quoted(e.name) + "\n";
  if (!e.description.empty()) y += "description: " + io::yaml_quoted(e.description) + "\n";
  auto field = [&](const char* key, double x, const char* unit) {
    std::string l = std::string(key) + ": " + io::format_scene_number(x);
    if (unit) l += std::string(l.size() < 28 ? 28 - l.size() : 1, ' ') + "# " + unit;
    y += l + "\n";
  };
  field("mass", e.mass_kg, "kg");
  field("k_L", e.k_L, "N/m");
  field("v", e.v, "m/s");
  field("E", e.E, "Pa");
  field("nu", e.nu, nullptr);
  field("sigma_exp", e.sigma_exp, "Pa");
  y += "junctions: " + io::yaml_quoted(junctions_rel) + "\n";
  if (!measured_rel.empty()) y += "measured: " + io::yaml_quoted(measured_rel) + "\n";
  return y;
}

}  // namespace asperity
