// The bridge from attenuvis::mie to the bulk integrals.
#include "attenuvis/mie.hpp"
#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather {

BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s) {
  EfficiencyFunction q = [m](double x) {
    auto e = mie::sphere(x, m);
    return Efficiency{e.qext, e.qsca, e.qabs, e.g};
  };
  return integrate_bulk_optics(d, wavelength_m, q, s, m);
}

}  // namespace attenuvis::weather
