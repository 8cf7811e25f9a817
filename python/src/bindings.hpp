// One function per library module, each in its own bind_<module>.cpp.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace attenuvis::visgraph {
class Scene;
}

namespace attenuvis::python {

// NumPy arrays as the visgraph, space-syntax and weather bindings take them:
// C order, converted from any numeric dtype.
using Doubles = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;
using Indices = pybind11::array_t<std::uint32_t, pybind11::array::c_style | pybind11::array::forcecast>;

void bind_mie(pybind11::module_ module);
void bind_weather(pybind11::module_ module);
void bind_visgraph(pybind11::module_ module);
// Space syntax over the visgraph module's scenes (bind_space_syntax.cpp).
void bind_space_syntax(pybind11::module_ module);

// The C++ scene inside a visgraph.Scene of the extension (bind_visgraph.cpp).
const visgraph::Scene& scene_of(pybind11::handle scene);
// An (N, 3) array of x, y, z as points; throws naming `what` otherwise (bind_visgraph.cpp).
std::vector<Eigen::Vector3d> points(const Doubles& array, const char* what);

}  // namespace attenuvis::python
