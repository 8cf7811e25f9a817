// The full bulk optics of a Mie condition (condition_optics.hpp).
#include "attenuvis/weather/condition_optics.hpp"

#include <cmath>
#include <stdexcept>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/aerosol_optics.hpp"
#include "attenuvis/weather/coated_optics.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "real_axis_settings.hpp"

namespace attenuvis::weather {

void check_scattering_angles(const std::vector<double>& angles_deg) {
  for (std::size_t i = 0; i < angles_deg.size(); ++i) {
    const double a = angles_deg[i];
    if (!(a >= 0 && a <= 180))
      throw std::invalid_argument("scattering angle " + std::to_string(i + 1) + " (" + io::shortest(a) +
                                  " deg) is outside [0, 180]");
  }
}

ConditionOptics condition_optics(const MieCondition& c, double wavelength_m, const Settings& s,
                                 const OpticsRequest& request) {
  if (request.legendre_moments < -1) throw std::invalid_argument("Legendre moments: L must be >= 0");
  check_scattering_angles(request.angles_deg);
  ConditionOptics out;
  out.wavelength_m = wavelength_m;
  const std::complex<double> m = condition_refractive_index(c, wavelength_m, s, &out.index_source);
  const SizeDistribution d = condition_distribution(c);
  out.distribution = d.describe();
  // As sigma() on the real axis: rain at short wavelengths gives sigma_ext alone.
  QuadratureSettings q = detail::real_axis_settings(c, s);
  q.backscatter = request.backscatter;
  q.legendre_moments = request.legendre_moments;
  q.angles_deg = request.angles_deg;
  q.polarised = request.polarised;
  out.bulk = c.coating ? coated_bulk_optics(d, wavelength_m, m, *c.coating, q) : mie_bulk_optics(d, wavelength_m, m, q);
  return out;
}

ConditionOptics condition_optics(const Condition& c, double wavelength_m, const Settings& s,
                                 const OpticsRequest& request) {
  if (const auto* mie = std::get_if<MieCondition>(&c)) return condition_optics(*mie, wavelength_m, s, request);
  const auto* aerosol = std::get_if<AerosolCondition>(&c);
  if (!aerosol)
    throw std::invalid_argument("'" + to_text(c) + "' has no particles: bulk optics need a Mie condition or an aerosol");
  const AerosolOptics a = aerosol_optics(*aerosol, wavelength_m, s, request);
  ConditionOptics out;
  out.bulk = a.bulk;
  out.wavelength_m = wavelength_m;
  out.index_source = a.index_source;
  out.distribution = a.model;
  return out;
}

}  // namespace attenuvis::weather
