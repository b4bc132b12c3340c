#include "regress/regress_io.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "io/yaml_util.hpp"
#include "regress/regress.hpp"
#include "scene/load.hpp"

namespace asperity {
namespace fs = std::filesystem;
using io::MapView;
using io::Source;

RegressSuite load_regress_suite(const fs::path& yaml) {
  const std::string display = yaml.string();
  const YAML::Node root = io::load_yaml_file(yaml, display);
  const Source src{display};
  const MapView top(src, root, "", {"entries"}, 1);
  const YAML::Node list = top.require("entries");
  if (!list.IsSequence() || list.size() == 0) top.fail_at(list, "entries", "expected a non-empty list of entries");
  RegressSuite suite;
  suite.file = yaml;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "entries[" + std::to_string(i) + "]";
    const MapView e(src, list[i], path, {"name", "scene", "set"});
    RegressEntry r;
    r.name = e.string(e.require("name"), "name");
    if (r.name.empty() || r.name.find_first_of(" :#\t") != std::string::npos)
      e.fail_at(e.require("name"), "name", "names are non-empty words without spaces, ':' or '#'");
    if (!names.insert(r.name).second) e.fail_at(e.require("name"), "name", "duplicate entry name '" + r.name + "'");
    const YAML::Node scene_node = e.require("scene");
    const std::string scene = e.string(scene_node, "scene");
    r.scene = yaml.parent_path() / scene;
    if (!fs::is_regular_file(r.scene)) e.fail_at(scene_node, "scene", "scene file not found: '" + scene + "'");
    if (auto s = e.find("set")) r.overrides = e.string_list(*s, "set");
    suite.entries.push_back(std::move(r));
  }
  return suite;
}

Golden load_golden(const fs::path& yaml) {
  const std::string display = yaml.string();
  const YAML::Node root = io::load_yaml_file(yaml, display);
  const Source src{display};
  const MapView top(src, root, "", {"history", "entries"}, 1);
  Golden g;
  if (auto h = top.find("history"); h && !h->IsNull()) {
    if (!h->IsSequence()) top.fail_at(*h, "history", "expected a list");
    for (std::size_t i = 0; i < h->size(); ++i) {
      const MapView r(src, (*h)[i], "history[" + std::to_string(i) + "]", {"date", "version", "reason"});
      g.history.push_back({r.string(r.require("date"), "date"), r.string(r.require("version"), "version"),
                           r.string(r.require("reason"), "reason")});
    }
  }
  const YAML::Node entries = top.require("entries");
  if (!entries.IsMap()) top.fail_at(entries, "entries", "expected a map of entry name → observables");
  // Through MapView, so that a second value for one entry or observable is refused, not taken
  // silently (the last would win), and an observable no run computes is refused, not ignored.
  std::vector<std::string> names;
  for (const auto& kv : entries)
    if (kv.first.IsScalar()) names.push_back(kv.first.Scalar());
  std::vector<std::string> observables;
  for (const auto& [key, value] : regress_observables(Observables{})) observables.push_back(key);
  const MapView ev(src, entries, "entries", names);
  for (const std::string& name : names) {
    const YAML::Node obs = ev.require(name);
    if (!obs.IsMap()) ev.fail_at(obs, name, "expected a map of observable → {value, tolerance}");
    const MapView ov(src, obs, "entries." + name, observables);
    for (const auto& o : obs) {
      const std::string key = o.first.Scalar();
      const MapView v(src, o.second, "entries." + name + "." + key, {"value", "tolerance"});
      GoldenValue gv;
      // Non-finite values are legitimate observables (e.g. no stick-slip → drop NaN).
      const YAML::Node val = v.require("value");
      const std::string text = val.IsScalar() ? val.Scalar() : "";
      if (text == ".nan" || text == "nan")
        gv.value = std::nan("");
      else
        gv.value = v.number(val, "value", nullptr);
      gv.tolerance = v.number(v.require("tolerance"), "tolerance", nullptr);
      if (!(gv.tolerance >= 0)) v.fail_at(v.require("tolerance"), "tolerance", "must be >= 0");
      g.entries[name][key] = gv;
    }
  }
  return g;
}

std::string golden_to_yaml(const Golden& g) {
  std::ostringstream s;
  s << "# Golden results of `asperity regress` (scenes/regression/suite.yaml). Re-bless with\n"
       "# `asperity regress --update --reason \"...\"`, never by hand. Tolerances are absolute and\n"
       "# derived from the measured solver error of each entry (see README, Regression runs).\n";
  s << (g.history.empty() ? "history: []\n" : "history:\n");
  for (const auto& r : g.history)
    s << "  - {date: " << io::yaml_quoted(r.date) << ", version: " << io::yaml_quoted(r.version)
      << ", reason: " << io::yaml_quoted(r.reason) << "}\n";
  s << "entries:\n";
  for (const auto& [name, obs] : g.entries) {
    s << "  " << name << ":\n";
    for (const auto& [key, v] : obs)
      s << "    " << key << ": {value: " << (std::isnan(v.value) ? std::string(".nan") : io::format_double(v.value))
        << ", tolerance: " << io::format_double(v.tolerance) << "}\n";
  }
  return s.str();
}

}  // namespace asperity
