// What a sigma computation needs besides the condition and the wavelength
// (both arguments of sigma(), sigma.hpp).
#pragma once

#include <atomic>
#include <cstddef>
#include <string>

#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather {

// The settings every sigma depends on besides the condition and the wavelength.
struct Settings {
  Convention convention = Convention::itu;  // how P.1817 power laws are read (units.hpp)
  double contrast_threshold = 0.02;         // Koschmieder epsilon: 0.02 (3.912) or 0.05 (2.996)
  double rel_tolerance = 1e-9;              // Mie integrals: quadrature + tails, relative to sigma_ext
  // Mie integrals on the real axis: the budget of Mie evaluations per size
  // integral (QuadratureSettings::max_evaluations; nearly lossless particles
  // beyond it come back with the error reached, bulk_optics.hpp).
  std::size_t max_evaluations = 1000000;
  // Refractive-index table of Mie conditions that name none: a name or alias
  // in water_tables() (refractive_index.hpp), "water" = Hale & Querry (1973).
  // A condition's water= or m= overrides it.
  std::string water_table = "water";
  // Mie over rain drops: beyond this size parameter Q_ext's large-x expansion
  // (with its error bound, bulk_optics.hpp) replaces Mie.
  double rain_asymptotic_x = 2000;
  // Set by another thread to stop the computation: sigma(), condition_optics()
  // and sigma_table() then throw Cancelled (cancel.hpp).  Never read for results.
  const std::atomic<bool>* cancel = nullptr;
};

}  // namespace attenuvis::weather
