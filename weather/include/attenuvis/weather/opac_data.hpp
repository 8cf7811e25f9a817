// The numbers of the OPAC components, read at run time from data/opac/
// (its README carries their provenance and licence note):
//
//   size_distr.cfg   per component and tabulated humidity: Rmin, Rmax (um,
//                    the cut-offs), Rmod (um, the number median radius), rho
//                    (g/cm^3; the file's header says g/m^3, a typo), sigma
//                    (the geometric standard deviation)
//   refractive_indices/<name><RH>_refr.dat   wavelength (um, 0.25-40), n, k
//                    with k given negative (index_file.hpp: ImaginarySign::n_minus_ik)
//
// Each reader names the file and line of what it cannot read; the data are
// read once per process (thread-safe) and checked against OPAC's own
// invariants (every hygroscopic component at all eight humidities, in order;
// the others at 0 % only).
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/aerosol.hpp"
#include "attenuvis/weather/index_file.hpp"

namespace attenuvis::weather {

// One row of size_distr.cfg, in its own units.
struct OpacSizeRow {
  int component = 0;  // OPAC's number, 1..10
  double rh_percent = 0;
  double r_min_um = 0, r_max_um = 0, r_mod_um = 0, density_g_cm3 = 0, sigma_g = 0;
  int line = 0;
};
// Throws std::runtime_error "SOURCE:LINE: what" for a row that is not seven
// numbers in range (component 1..10, RH 0..100, 0 < Rmin < Rmod < Rmax,
// density > 0, sigma > 1).
std::vector<OpacSizeRow> parse_opac_size_table(const std::string& text, const std::string& source);

// A component at one tabulated humidity, in SI.
struct OpacState {
  double rh_percent = 0;
  double r_min_m = 0, r_max_m = 0, r_mod_m = 0, sigma_g = 0;
  double density_kg_m3 = 0;
  MaterialIndex index;  // m = n + ik, k >= 0
};
struct OpacComponentData {
  AerosolComponent component;
  std::vector<OpacState> states;  // increasing RH, the first at 0 %
};

// A component's data from data_directory()/opac (read once).  Throws
// std::runtime_error naming the file when it is missing or malformed.
const OpacComponentData& opac_component(AerosolComponent c);

// "<data>/opac/refractive_indices/waso70_refr.dat".
std::string opac_index_path(AerosolComponent c, double rh_percent);

}  // namespace attenuvis::weather
