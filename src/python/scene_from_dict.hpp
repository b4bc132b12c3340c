#pragma once
// Scenes from Python objects: a Python value becomes the YAML node its text would parse to, so that
// the scene loader checks a dict exactly as it checks a file.
#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "scene/scene.hpp"

namespace asperity::python {

// dicts → maps, lists/tuples/arrays → lists, bool → true/false, numbers → their shortest
// round-trip text (read back bit for bit), str as is, None → null; `key` names the value in errors.
YAML::Node yaml_node(const pybind11::handle& v, const std::string& key);

// Scene.from_dict: the dict as a scene tree; junction arrays (or a DataFrame with the junctions
// CSV's columns area_m2, x_m, y_m) go in as experiment.junctions, a measured curve as
// experiment.measured; then the loader's own checks.
Scene scene_from_dict(const pybind11::dict& d, pybind11::object areas, pybind11::object x, pybind11::object y,
                      const pybind11::object& measured);

}  // namespace asperity::python
