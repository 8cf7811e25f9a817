// Large-x expansion of Q_ext and the resonance threshold (see resonance.hpp).
#include "resonance.hpp"

#include <cmath>

namespace attenuvis::weather {

// At k = 1e-3 the absorption width of a resonance, ~2 k x / n, is >= 0.15 for
// x >= 100, resolved by the adaptive rule's panels.
double resonance_free_k() { return 1e-3; }

double qext_asymptotic(double x) { return 2.0 + 1.9924 * std::pow(x, -2.0 / 3.0); }

double qext_asymptotic_bound(double x, std::complex<double> m) {
  return (40.0 + 8.0 / std::max(std::abs(m.real() - 1.0), 1e-3)) / x;
}

}  // namespace attenuvis::weather
