// The bridge from attenuvis::mie to the bulk integrals.
#include <stdexcept>

#include "attenuvis/weather/bulk_optics.hpp"

#if __has_include("attenuvis/mie.hpp")
#include "attenuvis/mie.hpp"
#define ATTENUVIS_HAVE_MIE 1
#endif

namespace attenuvis::weather {

BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s) {
#ifdef ATTENUVIS_HAVE_MIE
  EfficiencyFunction q = [m](double x) {
    auto e = mie::sphere(x, m);
    return Efficiency{e.qext, e.qsca, e.qabs, e.g};
  };
  return integrate_bulk_optics(d, wavelength_m, q, s, m);
#else
  (void)d; (void)wavelength_m; (void)m; (void)s;
  throw std::runtime_error("attenuvis::mie is not available in this build");
#endif
}

}  // namespace attenuvis::weather
