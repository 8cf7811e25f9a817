// The bridge from attenuvis::mie to the bulk integrals (bulk_optics.hpp):
// Lorenz-Mie efficiencies as an EfficiencyFunction, and bulk_optics() with them.
#include "attenuvis/mie.hpp"
#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather {

EfficiencyFunction mie_efficiencies(std::complex<double> m) {
  mie::Options options;
  if (std::abs(m - 1.0) >= 0.01) options.extended_above = 3e4;  // automatic precision: double-only up to there
  return [m, options](double x) {
    auto e = mie::sphere(x, m, options);
    return Efficiency{e.qext, e.qsca, e.qabs, e.g};
  };
}

BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s) {
  EfficiencyFunction q = [m](double x) {
    auto e = mie::sphere(x, m);
    return Efficiency{e.qext, e.qsca, e.qabs, e.g};
  };
  return integrate_bulk_optics(d, wavelength_m, q, s, m);
}

}  // namespace attenuvis::weather
