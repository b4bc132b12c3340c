#include "python/scene_from_dict.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"

namespace asperity::python {

namespace py = pybind11;

// A Python value as the YAML node its text would parse to, so that the scene loader checks a dict
// exactly as it checks a file: dicts → maps, lists/tuples/arrays → lists, bool → true/false,
// numbers → their shortest round-trip text (read back bit for bit), str as is, None → null.
YAML::Node yaml_node(const py::handle& v, const std::string& key) {
  if (v.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (PyBool_Check(v.ptr())) return YAML::Node(v.ptr() == Py_True ? "true" : "false");
  if (py::isinstance<py::str>(v)) return YAML::Node(v.cast<std::string>());
  if (PyLong_Check(v.ptr())) return YAML::Node(std::string(py::str(v)));
  if (PyFloat_Check(v.ptr())) return YAML::Node(io::format_double(v.cast<double>()));
  if (py::isinstance<py::dict>(v)) {
    YAML::Node m(YAML::NodeType::Map);
    for (const auto& [k, x] : v.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k))
        throw py::type_error(key + ": keys must be str, got " + std::string(py::repr(k)));
      const std::string name = k.cast<std::string>();
      m[name] = yaml_node(x, key.empty() ? name : key + "." + name);
    }
    return m;
  }
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v) || py::isinstance<py::array>(v)) {
    YAML::Node s(YAML::NodeType::Sequence);
    for (const py::handle x : py::isinstance<py::array>(v) ? v.attr("tolist")() : py::reinterpret_borrow<py::object>(v))
      s.push_back(yaml_node(x, key));
    return s;
  }
  if (py::hasattr(v, "__index__"))
    return YAML::Node(std::string(py::str(py::int_(py::reinterpret_borrow<py::object>(v)))));
  if (py::hasattr(v, "__float__")) return YAML::Node(io::format_double(v.cast<double>()));  // numpy floats
  throw py::type_error(key + ": expected a number, text, bool, list or dict, got " +
                       std::string(py::str(v.get_type().attr("__name__"))));
}

namespace {

// One junction column (array, list, pandas Series) as the inline list the loader checks value by
// value, as it checks the rows of a junctions CSV.
YAML::Node junction_column(const py::object& column, const std::string& where, const std::string& name) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  Array a = Array::ensure(column);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(name + ": expected numbers (a NumPy array, a list or a pandas column), got " +
                         std::string(py::str(column.get_type().attr("__name__"))));
  }
  if (a.ndim() != 1)
    throw io::InputError(
        where, 0, name,
        "expected one value per junction (one dimension), got " + std::to_string(a.ndim()) + " dimensions");
  YAML::Node s(YAML::NodeType::Sequence);
  const auto r = a.unchecked<1>();
  for (py::ssize_t i = 0; i < r.shape(0); ++i) s.push_back(YAML::Node(io::format_double(r(i))));
  return s;
}

// The measured curve (a DataFrame or a mapping with Q_N and A_m2) as experiment.measured.
YAML::Node measured_node(const py::object& measured, const std::string& where) {
  const py::object columns = py::hasattr(measured, "columns") ? measured.attr("columns") : measured.attr("keys")();
  YAML::Node m(YAML::NodeType::Map);
  for (const py::handle c : columns) {
    const std::string n = py::str(c);
    if (n != "Q_N" && n != "A_m2")
      throw io::InputError(where, 0, "measured", "unknown column " + io::quote(n) + "; valid: Q_N, A_m2");
    m[n] = junction_column(py::object(measured[c]), where, n);
  }
  return m;
}

}  // namespace

// Scene.from_dict: the dict as a scene tree; junction arrays (or a DataFrame with the junctions
// CSV's columns area_m2, x_m, y_m) go in as experiment.junctions, a measured curve as
// experiment.measured; then the loader's own checks.
Scene scene_from_dict(const py::dict& d, py::object areas, py::object x, py::object y, const py::object& measured) {
  const std::string where = "Scene.from_dict";
  YAML::Node tree = yaml_node(d, "");
  if (py::hasattr(areas, "columns")) {  // a pandas DataFrame
    if (!x.is_none() || !y.is_none())
      throw io::InputError(where, 0, "x", "give x_m and y_m as columns of the DataFrame or as arrays, not both");
    const py::object df = areas;
    areas = py::none();
    const std::vector<std::string> valid{"area_m2", "x_m", "y_m"};
    for (const py::handle c : df.attr("columns")) {
      const std::string n = py::str(c);
      if (std::find(valid.begin(), valid.end(), n) == valid.end())
        throw io::InputError(
            where, 0, "areas",
            "unknown column " + io::quote(n) + io::did_you_mean(n, valid) + "; valid: area_m2, x_m, y_m");
      (n == "area_m2" ? areas : n == "x_m" ? x : y) = py::object(df[c]);
    }
    if (areas.is_none()) throw io::InputError(where, 0, "areas", "missing column 'area_m2'");
  }
  if (areas.is_none()) {
    if (!x.is_none() || !y.is_none()) throw io::InputError(where, 0, "areas", "x and y need the junction areas");
    if (!measured.is_none()) throw io::InputError(where, 0, "measured", "needs the junction areas too");
  } else {
    const YAML::Node& view = tree;
    if (!view["experiment"].IsDefined() || view["experiment"].IsNull())
      tree["experiment"] = YAML::Node(YAML::NodeType::Map);
    YAML::Node e = tree["experiment"];
    if (!e.IsMap())
      throw io::InputError(where, 0, "experiment",
                           "with junction arrays, the experiment is a map of its values {name, mass, k_L, v, E, nu, "
                           "sigma_exp}, not a file");
    YAML::Node j(YAML::NodeType::Map);
    j["area_m2"] = junction_column(areas, where, "area_m2");
    if (!x.is_none()) j["x_m"] = junction_column(x, where, "x_m");
    if (!y.is_none()) j["y_m"] = junction_column(y, where, "y_m");
    e["junctions"] = j;
    if (!measured.is_none()) e["measured"] = measured_node(measured, where);
  }
  return scene_from_memory(tree, std::filesystem::current_path(), where);
}

}  // namespace asperity::python
