#include "scene/override.hpp"

#include <algorithm>
#include <cctype>

#include "io/yaml_util.hpp"
#include "scene/load.hpp"

namespace asperity {

using io::node_kind;
using io::strip_marks;

namespace {

std::vector<std::string> split_key(const std::string& dotted, const std::string& where) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    parts.push_back(dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    const std::string& p = parts.back();
    const bool ok = !p.empty() && std::all_of(p.begin(), p.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!ok) throw io::InputError(where, 0, dotted, "malformed key (expected names joined by dots, e.g. model.eta)");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

// Path copy: a new map for every level along `parts`, sharing all other nodes (and their Marks).
YAML::Node set_path(const YAML::Node& node, const std::vector<std::string>& parts, std::size_t i,
                    const YAML::Node& value, const std::string& where, const std::string& dotted) {
  const std::string here = [&] {
    std::string s;
    for (std::size_t j = 0; j < i; ++j) s += (j ? "." : "") + parts[j];
    return s;
  }();
  YAML::Node cur = node;
  // path → {file: path} (an experiment) or {recipe: path} (a topography recipe): values set
  // inside replace the file's.
  if (cur.IsDefined() && cur.IsScalar() && (here == "experiment" || here == "topography")) {
    YAML::Node m(YAML::NodeType::Map);
    m[YAML::Node(here == "experiment" ? "file" : "recipe")] = cur;
    cur.reset(m);  // rebind: `cur = m` would turn the caller's (shared) node into the map
  }
  if (cur.IsDefined() && !cur.IsNull() && !cur.IsMap())
    throw io::InputError(
        where, 0, dotted,
        "cannot set " + dotted + ": " + (here.empty() ? "the scene" : here) + " is " + node_kind(cur) + ", not a map");
  auto child_value = [&](const YAML::Node& old) {
    return i + 1 == parts.size() ? value : set_path(old, parts, i + 1, value, where, dotted);
  };
  YAML::Node out(YAML::NodeType::Map);
  bool replaced = false;
  if (cur.IsDefined() && cur.IsMap()) {
    for (auto it = cur.begin(); it != cur.end(); ++it) {
      if (!replaced && it->first.IsScalar() && it->first.Scalar() == parts[i]) {
        out[it->first] = child_value(it->second);  // keeps the original key node (and its line)
        replaced = true;
      } else {
        out[it->first] = it->second;
      }
    }
  }
  if (!replaced) out[YAML::Node(parts[i])] = child_value(YAML::Node(YAML::NodeType::Null));
  return out;
}

}  // namespace

YAML::Node apply_override_at(const YAML::Node& tree, const std::string& dotted, const YAML::Node& value,
                             const std::string& where) {
  const std::vector<std::string> parts = split_key(dotted, where);
  if (!value.IsDefined()) throw io::InputError(where, 0, dotted, "undefined value");
  return set_path(tree, parts, 0, strip_marks(value), where, dotted);
}

YAML::Node apply_override(YAML::Node scene_tree, const std::string& dotted_key, const YAML::Node& value) {
  return apply_override_at(scene_tree, dotted_key, value, "override " + dotted_key);
}

}  // namespace asperity
