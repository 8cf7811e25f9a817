// Aerosols as OPAC describes them (M. Hess, P. Koepke and I. Schult, "Optical
// Properties of Aerosols and Clouds: The software package OPAC", Bull. Amer.
// Meteor. Soc. 79, 831-844, 1998): ten components, each a log-normal number
// distribution of homogeneous spheres with a refractive index per wavelength,
// the hygroscopic ones tabulated at eight humidities; and the standard
// mixtures, external mixtures of components by number density.  Three
// registries, read by the condition grammar (haze:TYPE, aerosol:COMP=N,...,
// :growth=RULE), --help, the messages, Python and the documentation
// (registry.hpp):
//
//   aerosol_components   inso waso soot ssam sscm minm miam micm mitr suso   (Hess et al. 1998, Table 1)
//   aerosol_mixtures     continental-clean ... antarctic                      (Hess et al. 1998, Table 4)
//   humidity_rules       kappa (default), linear, nearest                     (humidity_growth.hpp)
//
// The numbers of each component (size distribution, density, refractive
// index) are read at run time from data/opac/ (opac_data.hpp).
#pragma once

#include <string>
#include <vector>

namespace attenuvis::weather {

// OPAC's ten components (Hess et al. 1998, Table 1), in OPAC's numbering.
enum class AerosolComponent { inso, waso, soot, ssam, sscm, minm, miam, micm, mitr, suso };
// A component's row of the registry: its name, OPAC number, help and growth.
struct AerosolComponentInfo {
  AerosolComponent id;
  std::string name;       // "waso": as OPAC, the grammar and Python spell it
  int opac_number;        // its number in OPAC's size_distr.cfg (1..10)
  std::string help;       // "water-soluble (sulfates, nitrates, organics)"
  bool hygroscopic;       // tabulated at 0, 50, 70, 80, 90, 95, 98, 99 % RH; else at 0 % only
};
// Every component, in the order of the enum (OPAC's numbering).
const std::vector<AerosolComponentInfo>& aerosol_components();
const AerosolComponentInfo& info(AerosolComponent c);
const AerosolComponentInfo* find_aerosol_component(const std::string& name);  // nullptr for any other name
std::string to_string(AerosolComponent c);
std::string aerosol_component_names();  // "inso, waso, ... or suso" for messages

// The humidities OPAC tabulates its hygroscopic components at (%).
const std::vector<double>& opac_humidities();

// A component and its number density (particles per cm^3 of the dry
// distribution; OPAC's N_i, unchanged by growth).
struct AerosolAmount {
  AerosolComponent component;
  double per_cm3 = 0;
};

// OPAC's ten aerosol types (Hess et al. 1998, Table 4).
enum class AerosolMixture {
  continental_clean,
  continental_average,
  continental_polluted,
  urban,
  desert,
  maritime_clean,
  maritime_polluted,
  maritime_tropical,
  arctic,
  antarctic
};
// A type's row of the registry: its name, help and components' amounts.
struct AerosolMixtureInfo {
  AerosolMixture id;
  std::string name;                   // "continental-average": haze:continental-average
  std::string help;                   // "continental, average"
  std::vector<AerosolAmount> amounts;  // Hess et al. 1998, Table 4
};
// Every type in the order of the enum; the row of one; the row of a name
// (nullptr for any other); its name; the names for messages.
const std::vector<AerosolMixtureInfo>& aerosol_mixtures();
const AerosolMixtureInfo& info(AerosolMixture m);
const AerosolMixtureInfo* find_aerosol_mixture(const std::string& name);
std::string to_string(AerosolMixture m);
std::string aerosol_mixture_names();
// "Hess, Koepke & Schult 1998, ...": the source of both tables.
const std::string& opac_citation();

// How a hygroscopic component is taken to a humidity between OPAC's
// (humidity_growth.hpp says how each works and why kappa is the default).
enum class HumidityRule { kappa, linear, nearest };
struct HumidityRuleInfo {
  HumidityRule id;
  std::string name;  // "kappa": :growth=kappa
  std::string help;
  std::string source;
};
const std::vector<HumidityRuleInfo>& humidity_rules();  // the first is the default
const HumidityRuleInfo& info(HumidityRule r);
const HumidityRuleInfo* find_humidity_rule(const std::string& name);
std::string to_string(HumidityRule r);

}  // namespace attenuvis::weather
