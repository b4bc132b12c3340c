#include "python/topography_bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "scene/topography_junctions.hpp"
#include "scene/topography_recipe.hpp"
#include "surface/height_map_io.hpp"
#include "surface/tangential_contact.hpp"

namespace py = pybind11;

namespace asperity::python {
namespace {

// A height map from NumPy (n × n, metres, without the sphere) and the recipe of its contact, checked
// as `asperity generate` checks a measured map (square, side, pixel, finite heights, their span) and
// a recipe's numbers; errors name the argument (`where`: the Python function).
struct SurfaceContactInput {
  HeightMap map;
  TopographyRecipe recipe;
};
SurfaceContactInput surface_contact_input(const std::string& where, const py::object& heights, double pixel_m,
                                          double sphere_radius_m, double load_N, double E, double nu, double tolerance,
                                          int max_iterations, int connectivity) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  Array a = Array::ensure(heights);
  if (!a) {
    PyErr_Clear();
    throw py::type_error("heights: expected a 2-D array of numbers, got " +
                         std::string(py::str(heights.get_type().attr("__name__"))));
  }
  if (a.ndim() != 2 || a.shape(0) != a.shape(1) || a.shape(0) < 2)
    throw io::InputError(where, 0, "heights", "expected a square n x n array with n >= 2");
  const auto n = static_cast<std::size_t>(a.shape(0));
  if (n > kMaxHeightMapSide)
    throw io::InputError(where, 0, "heights",
                         std::to_string(n) + " pixels a side: at most " + std::to_string(kMaxHeightMapSide));
  if (const std::string why = pixel_size_problem(pixel_m); !why.empty()) throw io::InputError(where, 0, "pixel_m", why);
  // The recipe's own ranges (scene/topography_recipe.hpp), named by the argument.
  const auto in_range = [&](const char* argument, const char* key, double v) {
    if (const std::string why = topography_number_problem(key, v); !why.empty())
      throw io::InputError(where, 0, argument, why);
  };
  in_range("sphere_radius_m", "sphere_radius_m", sphere_radius_m), in_range("load_N", "load_N", load_N);
  in_range("E", "E", E), in_range("nu", "nu", nu), in_range("tolerance", "contact.tolerance", tolerance);
  in_range("max_iterations", "contact.max_iterations", max_iterations);
  in_range("connectivity", "contact.connectivity", connectivity);
  SurfaceContactInput in;
  HeightMap& map = in.map;
  map.n = n;
  map.pixel_m = pixel_m;
  map.h_m.assign(a.data(), a.data() + n * n);
  for (std::size_t k = 0; k < n * n; ++k)
    if (!std::isfinite(map.h_m[k]))
      throw io::InputError(where, 0, "heights",
                           "heights[" + std::to_string(k / n) + ", " + std::to_string(k % n) + "] is not finite");
  if (const auto p = height_range_problem(map)) throw io::InputError(where, 0, "heights", p->message);
  TopographyRecipe& r = in.recipe;
  r.name = "numpy";
  r.display = where;
  r.kind = TopographyKind::measured;
  r.n = n, r.pixel_m = pixel_m, r.sphere_radius_m = sphere_radius_m, r.E_Pa = E, r.nu = nu, r.load_N = load_N;
  r.tolerance = tolerance, r.max_iterations = max_iterations;
  r.connectivity = connectivity == 4 ? Connectivity::four : Connectivity::eight;
  return in;
}

py::array_t<double> double_array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// asperity.generate_junctions: the junctions `asperity generate` makes of a measured map.
py::dict generate_junctions(const py::object& heights, double pixel_m, double sphere_radius_m, double load_N, double E,
                            double nu, double tolerance, int max_iterations, int connectivity, int threads) {
  SurfaceContactInput in = surface_contact_input("generate_junctions", heights, pixel_m, sphere_radius_m, load_N, E, nu,
                                                 tolerance, max_iterations, connectivity);
  TopographyContact t;
  {
    py::gil_scoped_release release;
    t = solve_surface_contact(std::move(in.map), in.recipe, std::max(1, threads));
  }
  py::dict d;
  d["area_m2"] = double_array(t.junctions.area_m2);
  d["x_m"] = double_array(t.junctions.x_m);
  d["y_m"] = double_array(t.junctions.y_m);
  d["contact_area_m2"] = t.contact_area_m2;
  d["clusters"] = t.clusters;
  d["merges"] = t.merges;
  d["iterations"] = t.iterations;
  d["rms_height_m"] = t.rms_height_m;
  d["rms_slope"] = t.rms_slope;
  return d;
}

// asperity.tangential_contact: the normal contact of a NumPy map (as generate_junctions) and the
// tangential contact on its contact map (surface/tangential_contact.hpp), Q(δ) at the displacements.
py::dict tangential_contact(const py::object& heights, double pixel_m, double sphere_radius_m, double load_N,
                            const std::vector<double>& displacements_m, double shear_strength_Pa,
                            double friction_coefficient, double E, double nu, double tolerance, int max_iterations,
                            double tangential_tolerance, bool slip_maps, int threads) {
  const std::string where = "tangential_contact";
  SurfaceContactInput in =
      surface_contact_input(where, heights, pixel_m, sphere_radius_m, load_N, E, nu, tolerance, max_iterations, 8);
  if (nu != 0.5)
    throw io::InputError(where, 0, "nu", "the tangential contact is solved at nu = 0.5 only (docs/continuum.md)");
  if ((shear_strength_Pa > 0) == (friction_coefficient > 0))
    throw io::InputError(where, 0, "shear_strength_Pa", "give one bound: shear_strength_Pa or friction_coefficient");
  if (!std::isfinite(shear_strength_Pa) || shear_strength_Pa < 0)
    throw io::InputError(where, 0, "shear_strength_Pa", "must be finite and positive");
  if (!std::isfinite(friction_coefficient) || friction_coefficient < 0)
    throw io::InputError(where, 0, "friction_coefficient", "must be finite and positive");
  if (!(tangential_tolerance > 0)) throw io::InputError(where, 0, "tangential_tolerance", "must be positive");
  double last = 0;
  for (const double d : displacements_m) {
    if (!(d >= last) || !std::isfinite(d))
      throw io::InputError(where, 0, "displacements_m", "must be finite and increase from 0");
    last = d;
  }
  if (displacements_m.size() > 100000) throw io::InputError(where, 0, "displacements_m", "at most 100,000 points");
  TangentialCurve c;
  TopographyContact t;
  {
    py::gil_scoped_release release;
    NormalContact normal;
    t = solve_surface_contact(std::move(in.map), in.recipe, std::max(1, threads), &normal);
    TangentialContactSettings s;
    s.E_Pa = E, s.nu = nu, s.tolerance = tangential_tolerance, s.threads = std::max(1, threads);
    TangentialContact tc(t.n, t.pixel_m,
                         shear_strength_Pa > 0 ? shear_strength_bound(normal, shear_strength_Pa)
                                               : coulomb_bound(normal, friction_coefficient),
                         s);
    c = tangential_curve(tc, displacements_m, true, slip_maps);
  }
  std::vector<double> Q, k, slip;
  bool converged = true;
  for (const TangentialCurvePoint& p : c.points)
    Q.push_back(p.force_N), k.push_back(p.tangent_stiffness_N_per_m), slip.push_back(p.slip_area_fraction),
        converged = converged && p.converged;
  py::dict d;
  d["displacement_m"] = double_array(displacements_m);
  d["force_N"] = double_array(Q);
  d["tangent_stiffness_N_per_m"] = double_array(k);
  d["slip_area_fraction"] = double_array(slip);
  d["initial_stiffness_N_per_m"] = c.initial_stiffness_N_per_m;
  d["full_sliding_force_N"] = c.full_sliding_force_N;
  d["full_sliding_displacement_m"] = c.full_sliding_displacement_m;
  d["contact_area_m2"] = t.contact_area_m2;
  d["converged"] = converged;
  d["monotone"] = c.monotone;
  if (slip_maps) {
    py::list maps;
    const auto n = static_cast<py::ssize_t>(t.n);
    for (const auto& m : c.slip_maps) maps.append(py::array_t<std::uint8_t>({n, n}, m.data()));
    d["slip_maps"] = maps;
  }
  return d;
}

}  // namespace

void bind_topography(py::module_& m) {
  m.def("generate_junctions", &generate_junctions, py::arg("heights"), py::arg("pixel_m"), py::arg("sphere_radius_m"),
        py::arg("load_N"), py::arg("E"), py::arg("nu"), py::arg("tolerance"), py::arg("max_iterations"),
        py::arg("connectivity"), py::arg("threads"));
  m.def("tangential_contact", &tangential_contact, py::arg("heights"), py::arg("pixel_m"), py::arg("sphere_radius_m"),
        py::arg("load_N"), py::arg("displacements_m"), py::arg("shear_strength_Pa"), py::arg("friction_coefficient"),
        py::arg("E"), py::arg("nu"), py::arg("tolerance"), py::arg("max_iterations"), py::arg("tangential_tolerance"),
        py::arg("slip_maps"), py::arg("threads"));
}

}  // namespace asperity::python
