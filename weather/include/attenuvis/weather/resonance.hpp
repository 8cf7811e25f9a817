// Error terms for what a smooth quadrature rule cannot see in Q_ext(x):
// the morphology-dependent resonances of nearly non-absorbing spheres, and the
// large-x expansion used in place of Mie for raindrops.  See resonance.cpp
// for the derivation and calibration of each bound.
#pragma once

#include <complex>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// Imaginary index above which resonances are absorption-broadened enough for
// the adaptive rule to resolve them (the resonance term is then zero).
double resonance_free_k();

// Bound on |sigma_ext(true) - sigma_ext(quadrature)| due to unresolved
// resonances, for radii in [r_lo, r_hi] (1/m).  Zero when Im(m) >= resonance_free_k().
double unresolved_resonance_bound(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                                  double r_lo_m, double r_hi_m, double asymptotic_x);

}  // namespace attenuvis::weather
