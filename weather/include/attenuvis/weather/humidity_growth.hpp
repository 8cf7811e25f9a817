// An OPAC component at a relative humidity: the populations of homogeneous
// spheres it stands for, by the humidity rule (aerosol.hpp: humidity_rules).
//
// At OPAC's own humidities (0, 50, 70, 80, 90, 95, 98, 99 %) every rule gives
// the tabulated state itself: the log-normal (Rmod, sigma, Rmin, Rmax), the
// density and the index file of that humidity.  Non-hygroscopic components
// have the 0 % state only and ignore the humidity.  Between tabulated
// humidities RH_i < RH < RH_i+1:
//
//   kappa (default)  One grown population.  The growth factor g = Rmod/Rmod_dry
//     follows kappa-Koehler theory (Petters & Kreidenweis 2007, ACP 7:1961,
//     eq. 11 with the Kelvin term left out, a_w = RH/100):
//         g^3 = 1 + kappa a_w / (1 - a_w),
//     with kappa fitted to the table at each tabulated humidity,
//     kappa_i = (g_i^3 - 1)(1 - a_i)/a_i, and taken linear in RH between them
//     (kappa_50 below 50 %).  One kappa for all humidities does not reproduce
//     OPAC's growth (Haenel's, below): for waso it would have to be
//     0.89 at 50 % and 0.15 at 99 % (fitted_kappa and the report give the
//     misfit), so kappa is fitted where the table speaks and interpolated
//     between.  sigma is kept (OPAC keeps it at every humidity); the cut-offs
//     follow ln Rmin, ln Rmax linear in ln g between the neighbours.  The
//     grown particle's index and density are volume-weighted between dry
//     matter and water, as OPAC's own tables are (G. Haenel, Adv. Geophys. 19,
//     73-188, 1976; the tables obey it: tests/weather/test_humidity_growth.cpp
//     recovers water's index, 1.333 at 550 nm, from every humid state): with
//     the water volume fraction f = 1 - 1/g^3, m and rho are linear in f
//     between the two neighbouring tabulated states, which is that rule with
//     the water the table itself implies.
//   linear  The two neighbouring states as an external mixture with the
//     component's particles split (RH_i+1 - RH)/(RH_i+1 - RH_i) : (RH - RH_i)/(...):
//     every extensive quantity (sigma_ext, sigma_sca, beta_pi, sigma_sca g,
//     sigma_sca chi_l) is then interpolated linearly in RH, the ratios (albedo,
//     g, lidar ratio) follow from them.  Twice the Mie work of kappa, and a
//     chord of sigma(RH), which is convex: up to 10 % above kappa's curve
//     between 95 and 98 % (urban and maritime haze at 550 nm).
//   nearest  The nearest tabulated state (ties: the lower), as libRadtran
//     does; a step function of RH.
//
// kappa is the default: one Mie integral per component, continuous and
// monotone in RH for every hygroscopic component, with the growth curve's
// own shape between the table's points.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "attenuvis/weather/aerosol.hpp"
#include "attenuvis/weather/opac_data.hpp"

namespace attenuvis::weather {

// One log-normal population of spheres of one component in one state.
struct AerosolPopulation {
  AerosolComponent component;
  double weight = 1;          // its share of the component's particles (linear: the two neighbours)
  double rh_percent = 0;      // the humidity of this state
  double growth_factor = 1;   // Rmod / Rmod(0 %)
  double r_mod_m = 0, sigma_g = 0, r_min_m = 0, r_max_m = 0;
  double density_kg_m3 = 0;
  // The index: m = (1 - t) m_lower + t m_upper of two tabulated states (t = 0: one state).
  const OpacState* lower = nullptr;
  const OpacState* upper = nullptr;
  double upper_share = 0;

  std::complex<double> index_at(double wavelength_m) const;
  // "waso at 85 % RH (kappa growth, g = 1.61)": for models and notes.
  std::string describe() const;
  // A key that identifies the state (component, humidity, rule): the cache of per-particle optics.
  std::string key() const;
};

// The populations of component c at rh_percent in [0, 99] by `rule`: one for
// kappa and nearest (and at tabulated humidities), two for linear between
// them.  Throws std::invalid_argument for RH outside [0, 99].
std::vector<AerosolPopulation> component_populations(AerosolComponent c, double rh_percent, HumidityRule rule);

// kappa-Koehler without the Kelvin term: kappa of a growth factor at a
// humidity, and the growth factor of a kappa (rh in percent, < 100).
double kappa_of_growth(double growth_factor, double rh_percent);
double growth_of_kappa(double kappa, double rh_percent);

// The one kappa that fits a hygroscopic component's tabulated growth best
// (least squares in g^3 - 1 over 50..99 %), and the largest relative error
// of its growth factor against the table: how far a single kappa is from OPAC.
struct KappaFit {
  double kappa = 0;
  double max_growth_error = 0;
};
KappaFit single_kappa_fit(AerosolComponent c);

}  // namespace attenuvis::weather
