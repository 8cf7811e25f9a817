// Bounds for what the quadrature cannot resolve in Q_ext(x).
#include "attenuvis/weather/resonance.hpp"

#include <cmath>

#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather {

double resonance_free_k() { return 1e-3; }

double unresolved_resonance_bound(const SizeDistribution&, double, std::complex<double> m, double, double, double) {
  if (m.imag() >= resonance_free_k()) return 0;
  return 0;  // TODO calibrated below
}

double qext_asymptotic(double x) { return 2.0 + 1.9924 * std::pow(x, -2.0 / 3.0); }

double qext_asymptotic_bound(double x, std::complex<double>) { return 10.0 / x; }

}  // namespace attenuvis::weather
