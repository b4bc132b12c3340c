#pragma once
// The Python bindings of the topography layer: asperity.generate_junctions (a NumPy height map →
// junctions, as `asperity generate` with a measured map) and asperity.tangential_contact (its
// continuum tangential contact, docs/continuum.md).
#include <pybind11/pybind11.h>

namespace asperity::python {

void bind_topography(pybind11::module_& m);

}  // namespace asperity::python
