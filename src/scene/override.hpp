#pragma once
// Internal to src/scene: setting one dotted key in a scene tree (load.hpp's apply_override),
// with errors reported against `where` (an override's text, e.g. "--set model.eta=abc").
#include <yaml-cpp/yaml.h>

#include <string>

namespace asperity {

YAML::Node apply_override_at(const YAML::Node& tree, const std::string& dotted, const YAML::Node& value,
                             const std::string& where);

}  // namespace asperity
