#include "studies/study_load.hpp"

#include <yaml-cpp/yaml.h>

#include <system_error>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::did_you_mean;
using io::fail;
using io::format_double;
using io::input_file_problem;
using io::kMaxYamlBytes;
using io::load_yaml_file;
using io::MapView;
using io::node_kind;
using io::quote;
using io::Source;

namespace {

const std::vector<std::string> kCommonKeys{"study", "description", "out", "threads"};

std::vector<std::string> with_common(std::vector<std::string> keys) {
  keys.insert(keys.begin(), kCommonKeys.begin(), kCommonKeys.end());
  return keys;
}

// A path of the study file: relative ones against its folder, lexically normal.
fs::path path_at(const MapView& m, const fs::path& folder, const YAML::Node& n, const std::string& k) {
  const std::string text = m.string(n, k);
  if (text.empty()) m.fail_at(n, k, "empty path");
  return (folder / text).lexically_normal();
}

// An input the study cannot run without: it must be a regular file.
fs::path input_file_at(const MapView& m, const fs::path& folder, const YAML::Node& n, const std::string& k) {
  const fs::path p = path_at(m, folder, n, k);
  const std::string problem = input_file_problem(p, kMaxYamlBytes);
  if (!problem.empty()) m.fail_at(n, k, quote(n.Scalar()) + ": " + problem + " (looked for " + p.string() + ")");
  return p;
}

// A list of paths. Inputs the study cannot run without: non-empty, each a regular file, none
// listed twice. Results of other commands: read when they exist (absent: no evidence).
enum class Listed { inputs, results };
std::vector<fs::path> files_at(const MapView& m, const fs::path& folder, const YAML::Node& n, const std::string& k,
                               Listed listed) {
  const bool inputs = listed == Listed::inputs;
  if (!n.IsSequence() || (inputs && n.size() == 0))
    m.fail_at(n, k,
              std::string(inputs ? "expected a non-empty list of files, got " : "expected a list of files, got ") +
                  node_kind(n));
  std::vector<fs::path> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string ki = k + "[" + std::to_string(i) + "]";
    if (!inputs) {
      out.push_back(path_at(m, folder, n[i], ki));
      continue;
    }
    out.push_back(input_file_at(m, folder, n[i], ki));
    for (std::size_t j = 0; j + 1 < out.size(); ++j) {
      std::error_code ec;
      if (fs::equivalent(out[j], out.back(), ec)) m.fail_at(n[i], ki, quote(n[i].Scalar()) + " listed twice");
    }
  }
  return out;
}

int integer_in(const MapView& m, const std::string& k, int lo, int hi, int fallback) {
  const auto n = m.find(k);
  if (!n) return fallback;
  const int v = m.integer(*n, k);
  if (v < lo || v > hi)
    m.fail_at(*n, k, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
  return v;
}

InteractionStudyOptions interactions_options(const MapView& m, const fs::path& folder) {
  InteractionStudyOptions o;
  o.scenes = files_at(m, folder, m.require("scenes"), "scenes", Listed::inputs);
  const MapView cal(m.source(), m.require("calibrations"), "calibrations", {"independent", "interacting"});
  o.fit_independent = path_at(cal, folder, cal.require("independent"), "independent");
  o.fit_interacting = path_at(cal, folder, cal.require("interacting"), "interacting");
  if (const auto j = m.find("joint")) {
    const MapView joint(m.source(), *j, "joint", {"independent", "interacting"});
    if (const auto n = joint.find("independent"))
      o.joint_independent = files_at(joint, folder, *n, "independent", Listed::results);
    if (const auto n = joint.find("interacting"))
      o.joint_interacting = files_at(joint, folder, *n, "interacting", Listed::results);
  }
  if (const auto n = m.find("sweep")) o.sweep_store = path_at(m, folder, *n, "sweep");
  if (const auto n = m.find("topography")) o.topography_table = path_at(m, folder, *n, "topography");
  if (const auto n = m.find("recovery")) o.recovery_matrix = path_at(m, folder, *n, "recovery");
  if (const auto n = m.find("spread_experiment")) o.spread_experiment = m.string(*n, "spread_experiment");
  o.threads = integer_in(m, "threads", 1, 1024, o.threads);
  return o;
}

RecoveryMatrixOptions recovery_options(const MapView& m, const fs::path& folder) {
  RecoveryMatrixOptions o;
  o.recipes = files_at(m, folder, m.require("recipes"), "recipes", Listed::inputs);
  const YAML::Node models = m.require("models");
  if (!models.IsSequence() || models.size() < 2)
    m.fail_at(models, "models", "expected a list of two fitting models or more, got " + node_kind(models));
  for (std::size_t i = 0; i < models.size(); ++i) {
    const MapView e(m.source(), models[i], m.key("models[" + std::to_string(i) + "]"),
                    {"label", "interactions", "fit"});
    RecoveryModel r;
    r.label = e.string(e.require("label"), "label");
    r.interactions = e.string(e.require("interactions"), "interactions");
    if (r.interactions != "none" && r.interactions != "elastic")
      e.fail_at(e.require("interactions"), "interactions",
                "unknown value " + quote(r.interactions) + "; valid: none, elastic");
    r.fit_template = input_file_at(e, folder, e.require("fit"), "fit");
    for (const RecoveryModel& before : o.models)
      if (before.label == r.label) e.fail_at(e.require("label"), "label", quote(r.label) + " given twice");
    o.models.push_back(r);
  }
  o.threads = integer_in(m, "threads", 1, 1024, o.threads);
  return o;
}

ContinuumStudyOptions continuum_options(const MapView& m, const fs::path& folder) {
  ContinuumStudyOptions o;
  o.recipe = input_file_at(m, folder, m.require("recipe"), "recipe");
  const YAML::Node loads = m.require("loads_N");
  if (!loads.IsSequence() || loads.size() == 0)
    m.fail_at(loads, "loads_N", "expected a non-empty list of loads [N], got " + node_kind(loads));
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const std::string k = "loads_N[" + std::to_string(i) + "]";
    const double load = m.number(loads[i], k, "N");
    if (!(load >= 1e-6 && load <= 1e6)) m.fail_at(loads[i], k, "must be in [1e-6, 1e6] N, got " + format_double(load));
    o.loads_N.push_back(load);
  }
  o.points = integer_in(m, "points", 2, 10000, o.points);
  o.threads = integer_in(m, "threads", 1, 1024, o.threads);
  return o;
}

}  // namespace

StudySpec load_study(const fs::path& yaml) {
  const std::string display = io::input_path(yaml);
  const Source src{display, nullptr};
  const YAML::Node root = load_yaml_file(yaml, display);
  if (!root.IsMap()) fail(src, root, "study", "expected a study file: a map with 'study: interactions' or the like");
  const std::vector<std::string> interactions_keys =
      with_common({"scenes", "calibrations", "joint", "sweep", "topography", "recovery", "spread_experiment"});
  const std::vector<std::string> recovery_keys = with_common({"recipes", "models"});
  const std::vector<std::string> continuum_keys = with_common({"recipe", "loads_N", "points"});
  std::vector<std::string> any_keys = interactions_keys;  // the kind is read first; then its own keys
  any_keys.insert(any_keys.end(), recovery_keys.begin() + kCommonKeys.size(), recovery_keys.end());
  any_keys.insert(any_keys.end(), continuum_keys.begin() + kCommonKeys.size(), continuum_keys.end());
  const MapView head(src, root, "", any_keys, 1);
  StudySpec s;
  s.file = yaml;
  const YAML::Node kind = head.require("study");
  s.kind = head.string(kind, "study");
  std::vector<std::string> keys;
  if (s.kind == "interactions")
    keys = interactions_keys;
  else if (s.kind == "recovery")
    keys = recovery_keys;
  else if (s.kind == "continuum")
    keys = continuum_keys;
  else
    head.fail_at(kind, "study",
                 "unknown study " + quote(s.kind) + did_you_mean(s.kind, {"interactions", "recovery", "continuum"}) +
                     "; valid: interactions, recovery, continuum");
  const MapView m(src, root, "", keys, 1);
  if (const auto d = m.find("description")) s.description = m.string(*d, "description");
  const fs::path folder = yaml.parent_path();
  const fs::path out = path_at(m, folder, m.require("out"), "out");
  if (s.kind == "interactions") {
    InteractionStudyOptions o = interactions_options(m, folder);
    o.out = out;
    o.study_file = yaml;
    s.options = o;
  } else if (s.kind == "recovery") {
    RecoveryMatrixOptions o = recovery_options(m, folder);
    o.out = out;
    o.study_file = yaml;
    s.options = o;
  } else {
    ContinuumStudyOptions o = continuum_options(m, folder);
    o.out = out;
    o.study_file = yaml;
    s.options = o;
  }
  return s;
}

}  // namespace asperity
