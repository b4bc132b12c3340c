// Scene and experiment files as text: fixed key order, shortest round-trip numbers,
// double-quoted strings; deterministic bytes.
#include <cmath>
#include <stdexcept>

#include "scene/load.hpp"
#include "io/numbers.hpp"

namespace asperity {

// A double-quoted YAML scalar with escapes (the one quoting used for every file we write).
std::string yaml_quoted(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20 || c == 0x7F) {
          out += "\\x";
          out += hex[c >> 4];
          out += hex[c & 0xF];
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

namespace {


std::string num(double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("cannot write a non-finite number to a scene file");
  return scene_io::format_double(x);
}

const char* name_of(JunctionShape s) { return s == JunctionShape::circular ? "circular" : "elliptic"; }
const char* name_of(AreaLaw a) { return a == AreaLaw::always ? "always" : "until_first_slip"; }
const char* name_of(SolverMethod m) { return m == SolverMethod::reference ? "reference" : "event"; }

}  // namespace

std::string model_solver_yaml(const ModelSettings& m, const SolverSettings& solver) {
  std::string y;
  y += "model:\n";
  y += "  eta: " + num(m.eta) + "\n";
  y += "  epsilon: " + num(m.epsilon) + "\n";
  y += "  c_min: " + num(m.c_min) + "\n";
  y += "  p: " + num(m.p) + "\n";
  y += "  alpha_b: " + num(m.alpha_b) + "\n";
  y += std::string("  junction_shape: ") + name_of(m.junction_shape) + "\n";
  y += std::string("  area_law: ") + name_of(m.area_law) + "\n";
  y += "solver:\n";
  y += std::string("  method: ") + name_of(solver.method) + "\n";
  y += "  Ct: " + num(solver.Ct) + "\n";
  y += "  tolerance: " + num(solver.tolerance) + "\n";
  return y;
}

std::string scene_to_yaml(const Scene& s) {
  const Experiment& e = s.experiment;
  const std::string file = e.file.empty() ? std::string() : std::filesystem::absolute(e.file).lexically_normal().string();
  std::string y;
  y += "# asperity scene, fully resolved: every value explicit, numbers round-trip exactly\n";
  y += "experiment:\n";
  y += "  file: " + yaml_quoted(file) + "\n";
  y += "  name: " + yaml_quoted(e.name) + "\n";
  y += "  description: " + yaml_quoted(e.description) + "\n";
  y += "  mass: " + num(e.mass_kg) + "\n";
  y += "  k_L: " + num(e.k_L) + "\n";
  y += "  v: " + num(e.v) + "\n";
  y += "  E: " + num(e.E) + "\n";
  y += "  nu: " + num(e.nu) + "\n";
  y += "  sigma_exp: " + num(e.sigma_exp) + "\n";
  y += model_solver_yaml(s.model, s.solver);
  y += "stop:\n";
  y += "  time: " + num(s.stop.time) + "\n";
  y += std::string("  at_first_peak: ") + (s.stop.at_first_peak ? "true" : "false") + "\n";
  y += "  cycles: " + std::to_string(s.stop.cycles) + "\n";
  // Limits only when set: a default one leaves the text (and so the sweep store's scene hash)
  // as it was before the keys existed.
  if (s.stop.wall_time != StopSettings{}.wall_time) y += "  wall_time: " + num(s.stop.wall_time) + "\n";
  if (s.stop.max_slips != 0) y += "  max_slips: " + std::to_string(s.stop.max_slips) + "\n";
  y += "output:\n";
  y += "  every: " + num(s.output.every) + "\n";
  y += "  series: [";
  for (std::size_t i = 0; i < s.output.series.size(); ++i) y += (i ? ", " : "") + s.output.series[i];
  y += "]\n";
  y += "  peak_min_drop: " + num(s.output.peak_min_drop) + "\n";
  return y;
}

std::string experiment_to_yaml(const Experiment& e, const std::string& junctions_rel, const std::string& measured_rel) {
  if (junctions_rel.empty()) throw std::invalid_argument("experiment_to_yaml: junctions_rel must not be empty");
  std::string y;
  y += "name: " + yaml_quoted(e.name) + "\n";
  if (!e.description.empty()) y += "description: " + yaml_quoted(e.description) + "\n";
  auto field = [&](const char* key, double x, const char* unit) {
    std::string l = std::string(key) + ": " + num(x);
    if (unit) l += std::string(l.size() < 28 ? 28 - l.size() : 1, ' ') + "# " + unit;
    y += l + "\n";
  };
  field("mass", e.mass_kg, "kg");
  field("k_L", e.k_L, "N/m");
  field("v", e.v, "m/s");
  field("E", e.E, "Pa");
  field("nu", e.nu, nullptr);
  field("sigma_exp", e.sigma_exp, "Pa");
  y += "junctions: " + yaml_quoted(junctions_rel) + "\n";
  if (!measured_rel.empty()) y += "measured: " + yaml_quoted(measured_rel) + "\n";
  return y;
}

}  // namespace asperity
