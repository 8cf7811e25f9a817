// One function per library module, each in its own bind_<module>.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace attenuvis::visgraph {
class Scene;
}

namespace attenuvis::python {

void bind_mie(pybind11::module_ module);
void bind_weather(pybind11::module_ module);
void bind_visgraph(pybind11::module_ module);
// Space syntax over the visgraph module's scenes (bind_space_syntax.cpp).
void bind_space_syntax(pybind11::module_ module);

// The C++ scene inside a visgraph.Scene of the extension (bind_visgraph.cpp).
const visgraph::Scene& scene_of(pybind11::handle scene);

}  // namespace attenuvis::python
