// The resonance threshold and the large-x expansion of Q_ext of the
// real-axis quadrature (bulk_optics.hpp).
//
// Nearly non-absorbing spheres (water in the visible, k ~ 2e-9) have
// morphology-dependent resonances in Q(x) whose widths (of order k x and
// narrower) no fixed sampling resolves.  When Im(m) < resonance_free_k(),
// bulk_optics locates them (mie/resonances.hpp), resolves those that matter
// with a panel each and bounds the rest (resonance_plan.hpp).
//
// Cost floor (validation/bench/weather_speed.cpp measures it): any rule must
// sample the ripple, a few nodes per 0.8 in x, up to the tail cut (x ~ 1600
// for advection fog at 550 nm), and a Mie evaluation costs ~0.06-0.09 us per
// unit of x, so the sum over nodes of Mie(x) is ~0.1-0.3 s on one core for
// advection fog before any resonance is resolved.
//
// For raindrops at visible wavelengths (x up to ~1e5) Mie is replaced beyond
// QuadratureSettings::asymptotic_x by the large-sphere expansion
//   Q_ext ~ 2 + 1.9924 x^(-2/3)                (edge term: Nussenzveig & Wiscombe,
//                                               Phys. Rev. Lett. 45, 1490 (1980))
// with the error bound |Q_ext - expansion| <= (40 + 8/|n - 1|) / x.  The bound
// is calibrated, not derived: sampling attenuvis::mie::sphere at 450 random x
// in [500, 3e4] for m = 1.333+1.96e-9i, 1.33, 1.34+1e-8i and 1.31+1e-3i gave
// max |Q_ext - expansion| x = 17.7; the 1/|n - 1| term follows the
// anomalous-diffraction ripple amplitude 4/rho = 2/(x (n - 1)) (van de Hulst
// 1957, Sec. 11.22) for indices closer to 1.
#pragma once

#include <complex>

namespace attenuvis::weather {

// Imaginary index above which resonances are absorption-broadened enough for
// the adaptive rule to resolve them (nothing located, no resonance error).
double resonance_free_k();

double qext_asymptotic(double x);
double qext_asymptotic_bound(double x, std::complex<double> m);

}  // namespace attenuvis::weather
