// The extension module attenuvis._attenuvis: one binding file per library
// module.  The pure-Python package (python/attenuvis) is the public face; the
// names here are its building blocks.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_attenuvis, module) {
  module.doc() = "attenuvis C++ core (use the attenuvis package, not this module)";
  attenuvis::python::bind_mie(module.def_submodule("mie", "Lorenz-Mie scattering by a homogeneous sphere"));
  attenuvis::python::bind_weather(module.def_submodule("weather", "Weather conditions and their extinction"));
  pybind11::module_ visgraph = module.def_submodule("visgraph", "Weather-weighted visibility graph");
  attenuvis::python::bind_visgraph(visgraph);
  attenuvis::python::bind_space_syntax(visgraph);
}
