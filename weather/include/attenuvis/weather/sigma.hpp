// The extinction coefficient of a condition at one wavelength.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/settings.hpp"

namespace attenuvis::weather {

// One part of a sigma's error estimate ("quadrature", "tails", ...), in 1/m;
// outputs convert it to the unit they print sigma in.
struct ErrorTerm {
  std::string name;
  double per_m = 0;
};

// The extinction coefficient of a condition, with its error, model and method.
struct Sigma {
  double per_m = 0;        // extinction coefficient, 1/m (neper)
  double error_per_m = 0;  // estimated bound on |per_m - true|; 0 for closed-form models (exact by definition)
  std::vector<ErrorTerm> error_terms;  // the parts of error_per_m (Mie conditions); they add up to it
  std::string model;       // what was computed, with its source
  std::string convention;  // "itu" or "seed" for power laws; "n/a" where the convention does not enter
  std::string note;        // warnings, refractive index used, integration method (numbers free of units)
  // Empty when the Mie integral met Settings::rel_tolerance; else what missed
  // it and by how much (BulkOptics::shortfall): error_per_m is then the
  // error reached, larger than the tolerance asked.
  std::string shortfall;
};

// Does Mie work only for a MieCondition.  Mie results are cached per process,
// keyed on the condition's value, the wavelength and the settings they depend
// on (conditions read from a file are not cached: the file may change).
Sigma sigma(const Condition& c, double wavelength_m, const Settings& s);

// The size distribution a Mie condition integrates over (after N=/lwc= rescaling).
SizeDistribution condition_distribution(const MieCondition& c);
// The refractive index a Mie condition uses at `wavelength_m`, and where it came from.
std::complex<double> condition_refractive_index(const MieCondition& c, double wavelength_m, const Settings& s,
                                                std::string* source = nullptr);
// Full Mie result (sigma_ext, sigma_sca, sigma_abs, albedo, g with errors) on the real axis.
BulkOptics condition_bulk_optics(const MieCondition& c, double wavelength_m, const Settings& s);

}  // namespace attenuvis::weather
