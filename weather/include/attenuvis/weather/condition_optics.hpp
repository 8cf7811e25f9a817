// Every bulk single-scattering quantity of a Mie condition at one wavelength:
// sigma_ext, sigma_sca, sigma_abs, albedo, g, and as requested the
// backscatter coefficient and lidar ratio, the Legendre moments chi_l and the
// phase function on an angle grid, each with its error (bulk_optics.hpp).
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/settings.hpp"

namespace attenuvis::weather {

// Which bulk quantities condition_optics() computes beyond sigma_ext ... g.
struct OpticsRequest {
  bool backscatter = true;
  int legendre_moments = -1;       // L >= 0: chi_0..chi_L
  std::vector<double> angles_deg;  // phase function at these angles, each in [0, 180]
  bool polarised = false;          // with legendre_moments >= 0: the whole matrix's expansion
};

// The bulk optics of a Mie condition at one wavelength, with how they were computed.
struct ConditionOptics {
  BulkOptics bulk;
  double wavelength_m = 0;
  std::string index_source;   // refractive index used, and where it came from
  std::string distribution;   // the size distribution, in the units it was given
};

// Throws std::invalid_argument naming the first angle (1-based) outside
// [0, 180] degrees; NaN is outside.
void check_scattering_angles(const std::vector<double>& angles_deg);

// Real-axis quadrature (the contour rule gives sigma_ext only).  Throws
// std::invalid_argument for an angle outside [0, 180] or L < -1, and what
// integrate_bulk_optics throws.
ConditionOptics condition_optics(const MieCondition& c, double wavelength_m, const Settings& s,
                                 const OpticsRequest& request);

// The same for any condition with particles (needs_mie: a Mie condition or an
// aerosol, aerosol_optics.hpp); throws std::invalid_argument for the others.
ConditionOptics condition_optics(const Condition& c, double wavelength_m, const Settings& s,
                                 const OpticsRequest& request);

}  // namespace attenuvis::weather
