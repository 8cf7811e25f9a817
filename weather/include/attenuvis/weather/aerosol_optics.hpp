// The bulk optics of an aerosol condition (condition.hpp: AerosolCondition):
// an external mixture, every quantity summed over its components'
// populations (humidity_growth.hpp) with their number densities,
//
//   sigma_x = sum_j N_j sigma_x,j          (ext, sca, abs, beta_pi: per particle, times N_j)
//   g = sum_j N_j g_j sigma_sca,j / sigma_sca,   chi_l and p(theta) likewise,
//
// each population's per-particle optics the certified real-axis quadrature
// of bulk_optics.hpp over its truncated log-normal, plus, as each integral's
// rounding error, the Lorenz-Mie efficiencies' own accuracy (1e-10 relative,
// floored at 1e-14 Q_ext: mie.hpp's referee bound), which the quadrature's
// Kronrod-Gauss differences cannot see and which dominates for the smallest
// components at long wavelengths, where the quadrature converges to ~1e-15
// relative.  The errors add: the sum's
// error is the sum of the populations' errors (quadrature, tails,
// resonances), and a ratio's error is bounded from those of its numerator
// and denominator, as bulk_optics.hpp bounds a single distribution's.
// Populations smaller than the wavelength cost what their series costs: at
// 10.6 um waso's x stays below 12 and its Mie series ends after a few terms.
//
// The tolerance (Settings::rel_tolerance, and the angular one of
// bulk_optics.hpp) is the mixture's.  Of P populations, one holding a share
// e of the mixture's sigma_ext (by the contour below, milliseconds) is
// integrated to max(1, 1/(P e)) times it, at most 0.5: a minor mode (coarse
// sea salt, <1 % of maritime sigma_ext) need not resolve its own resonances
// to the mixture's tolerance.  The mixture's reported errors then decide:
// if some quantity misses its tolerance, the loosened populations that met
// theirs are integrated again to the mixture's, and BulkOptics::shortfall
// names what the mixture (not a population) missed, and by how much.
//
// sigma_ext alone (aerosol_sigma of a condition, and the 550 nm integral of
// a visibility scaling) takes the segmented contour instead
// (segmented_contour.hpp: the cut log-normal is one analytic piece with a
// vertical leg at each cut), whose path passes above the resonances that the
// real axis must resolve one by one for nearly lossless particles: humid
// coarse sea salt at 550 nm to 1e-4 in ~700 evaluations and 3 ms, against
// ~5e5 and 1-2 s.  Where the contour does not apply, or its estimate exceeds
// Settings::max_evaluations, the real axis computes it.
//
// A visibility scaling multiplies every N_i by -ln(epsilon) / (V sigma_ext(550 nm))
// (epsilon = Settings::contrast_threshold, 0.02: 3.912/V); its uncertainty is
// that of sigma_ext(550 nm), added to the quadrature error of every scaled
// extensive quantity.  A mass scaling multiplies them by M / M_dry, the
// dry mass an exact moment of the truncated log-normals (no error of its own).
//
// Per-particle optics are kept per process (thread-safe, keyed by the
// population's state, the wavelength and what was asked), so a sweep over
// humidity, the 550 nm integrals of a visibility scaling and a table's
// repeated states are computed once.
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/condition_optics.hpp"
#include "attenuvis/weather/humidity_growth.hpp"
#include "attenuvis/weather/settings.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// A population and its number density (per cm^3, before any scaling).
struct AerosolPart {
  AerosolPopulation population;
  double per_cm3 = 0;
};
// The populations of every component of c at its humidity, by its rule.
std::vector<AerosolPart> aerosol_parts(const AerosolCondition& c);

// A population's truncated log-normal with `per_cm3` particles (the number of the uncut log-normal).
SizeDistribution population_distribution(const AerosolPopulation& p, double per_cm3);

// The dry mass concentration of c's amounts, in ug/m^3, before scaling:
// sum N_i rho_i 4/3 pi <r^3>_i of each component at 0 % RH within its cut-offs.
double aerosol_dry_mass_ug_m3(const AerosolCondition& c);

// The bulk optics of an aerosol condition (an external mixture) and how
// they were scaled.
struct AerosolOptics {
  BulkOptics bulk;             // the mixture, scaled
  double number_scale = 1;     // the visibility or mass scaling applied to every N_i (1: as given)
  double scale_error = 0;      // relative uncertainty of number_scale (in every extensive quadrature error)
  std::string model;           // the mixture, humidity, rule and scaling in words
  std::string index_source;    // where the populations' indices come from
};

// Throws std::invalid_argument for a wavelength outside the OPAC indices
// (0.25-40 um), and what integrate_bulk_optics throws.
AerosolOptics aerosol_optics(const AerosolCondition& c, double wavelength_m, const Settings& s,
                             const OpticsRequest& request);
// sigma_ext of computed optics, with its error terms; throws std::runtime_error if it is not finite.
Sigma aerosol_sigma(const AerosolOptics& o);
// sigma_ext alone, by the segmented contour where it applies (above).
Sigma aerosol_sigma(const AerosolCondition& c, double wavelength_m, const Settings& s);

// The external mixture of per-particle optics b_j with numbers n_j, as above.
BulkOptics external_mixture(const std::vector<const BulkOptics*>& optics, const std::vector<double>& numbers);

// "haze:urban" / "aerosol:waso=7000,soot=8300" at "95 % RH": the words of models and messages.
std::string aerosol_words(const AerosolCondition& c);

}  // namespace attenuvis::weather
