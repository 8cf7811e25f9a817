// One function per library module, each in its own bind_<module>.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace attenuvis::python {

void bind_mie(pybind11::module_ module);
void bind_weather(pybind11::module_ module);
void bind_visgraph(pybind11::module_ module);

}  // namespace attenuvis::python
