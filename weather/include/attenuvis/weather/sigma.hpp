// The extinction coefficient of a condition at one wavelength.
#pragma once

#include <string>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/settings.hpp"

namespace attenuvis::weather {

struct Sigma {
  double per_m = 0;        // extinction coefficient, 1/m (neper)
  double error_per_m = 0;  // estimated bound on |per_m - true|; 0 for closed-form models (exact by definition)
  std::string model;       // what was computed, with its source
  std::string convention;  // "itu" or "seed" for power laws; "n/a" where the convention does not enter
  std::string note;        // warnings, error breakdown, refractive index used
};

// Does Mie work only if the condition needs it (fog Mie, rain:R:mie).
Sigma sigma(const Condition& c, const Settings& s);

// The size distribution a Mie condition integrates over (after N=/lwc= rescaling).
SizeDistribution condition_distribution(const Condition& c);
// The refractive index a Mie condition uses at the settings' wavelength, and where it came from.
std::complex<double> condition_refractive_index(const Condition& c, const Settings& s, std::string* source = nullptr);
// Full Mie result (sigma_ext, sigma_sca, sigma_abs, albedo, g with errors) for a Mie condition.
BulkOptics condition_bulk_optics(const Condition& c, const Settings& s);

}  // namespace attenuvis::weather
