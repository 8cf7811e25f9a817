// The OPAC components, mixtures and humidity rules (aerosol.hpp).
#include "attenuvis/weather/aerosol.hpp"

#include "registry_rows.hpp"

namespace attenuvis::weather {

const std::string& opac_citation() {
  static const std::string citation =
      "M. Hess, P. Koepke and I. Schult, \"Optical Properties of Aerosols and Clouds: The software package OPAC\", "
      "Bull. Amer. Meteor. Soc. 79, 831-844 (1998)";
  return citation;
}

const std::vector<AerosolComponentInfo>& aerosol_components() {
  // Hess et al. 1998, Table 1 (the components and what they stand for).
  static const std::vector<AerosolComponentInfo> rows = [] {
    std::vector<AerosolComponentInfo> t = {
        {AerosolComponent::inso, "inso", 1, "insoluble (soil particles with some organic material)", false},
        {AerosolComponent::waso, "waso", 2, "water-soluble (sulfates, nitrates, organics)", true},
        {AerosolComponent::soot, "soot", 3, "soot (absorbing black carbon)", false},
        {AerosolComponent::ssam, "ssam", 4, "sea salt, accumulation mode", true},
        {AerosolComponent::sscm, "sscm", 5, "sea salt, coarse mode", true},
        {AerosolComponent::minm, "minm", 6, "mineral dust, nucleation mode", false},
        {AerosolComponent::miam, "miam", 7, "mineral dust, accumulation mode", false},
        {AerosolComponent::micm, "micm", 8, "mineral dust, coarse mode", false},
        {AerosolComponent::mitr, "mitr", 9, "mineral dust, transported (fewer large particles)", false},
        {AerosolComponent::suso, "suso", 10, "sulfate droplets (75 % H2SO4 solution)", true},
    };
    detail::check_enum_order(t, &AerosolComponentInfo::id);
    return t;
  }();
  return rows;
}

const AerosolComponentInfo& info(AerosolComponent c) { return detail::row_of(aerosol_components(), c); }
const AerosolComponentInfo* find_aerosol_component(const std::string& name) {
  return detail::find_by_name(aerosol_components(), name);
}
std::string to_string(AerosolComponent c) { return info(c).name; }
std::string aerosol_component_names() { return detail::name_list(detail::names_of(aerosol_components())); }

const std::vector<double>& opac_humidities() {
  static const std::vector<double> rh = {0, 50, 70, 80, 90, 95, 98, 99};
  return rh;
}

const std::vector<AerosolMixtureInfo>& aerosol_mixtures() {
  // Hess et al. 1998, Table 4: number densities (cm^-3) of the components of each
  // aerosol type; the OPAC program's own output for continental polluted
  // (inso 0.6, waso 15700, soot 34300) reads the same.
  using C = AerosolComponent;
  static const std::vector<AerosolMixtureInfo> rows = [] {
    std::vector<AerosolMixtureInfo> t = {
        {AerosolMixture::continental_clean, "continental-clean", "continental, clean", {{C::waso, 2600}, {C::inso, 0.15}}},
        {AerosolMixture::continental_average, "continental-average", "continental, average",
         {{C::waso, 7000}, {C::inso, 0.4}, {C::soot, 8300}}},
        {AerosolMixture::continental_polluted, "continental-polluted", "continental, polluted",
         {{C::waso, 15700}, {C::inso, 0.6}, {C::soot, 34300}}},
        {AerosolMixture::urban, "urban", "urban", {{C::waso, 28000}, {C::inso, 1.5}, {C::soot, 130000}}},
        {AerosolMixture::desert, "desert", "desert",
         {{C::waso, 2000}, {C::minm, 269.5}, {C::miam, 30.5}, {C::micm, 0.142}}},
        {AerosolMixture::maritime_clean, "maritime-clean", "maritime, clean",
         {{C::waso, 1500}, {C::ssam, 20}, {C::sscm, 3.2e-3}}},
        {AerosolMixture::maritime_polluted, "maritime-polluted", "maritime, polluted",
         {{C::waso, 3800}, {C::ssam, 20}, {C::sscm, 3.2e-3}, {C::soot, 5180}}},
        {AerosolMixture::maritime_tropical, "maritime-tropical", "maritime, tropical",
         {{C::waso, 590}, {C::ssam, 10}, {C::sscm, 1.3e-3}}},
        {AerosolMixture::arctic, "arctic", "arctic", {{C::inso, 0.01}, {C::waso, 1300}, {C::soot, 5300}, {C::ssam, 1.9}}},
        {AerosolMixture::antarctic, "antarctic", "antarctic", {{C::suso, 42.9}, {C::ssam, 0.047}, {C::mitr, 0.0053}}},
    };
    detail::check_enum_order(t, &AerosolMixtureInfo::id);
    return t;
  }();
  return rows;
}

const AerosolMixtureInfo& info(AerosolMixture m) { return detail::row_of(aerosol_mixtures(), m); }
const AerosolMixtureInfo* find_aerosol_mixture(const std::string& name) {
  return detail::find_by_name(aerosol_mixtures(), name);
}
std::string to_string(AerosolMixture m) { return info(m).name; }
std::string aerosol_mixture_names() { return detail::name_list(detail::names_of(aerosol_mixtures())); }

const std::vector<HumidityRuleInfo>& humidity_rules() {
  static const std::vector<HumidityRuleInfo> rows = [] {
    std::vector<HumidityRuleInfo> t = {
        {HumidityRule::kappa, "kappa",
         "kappa-Koehler growth between OPAC's humidities, kappa fitted to the table at each tabulated RH and "
         "interpolated linearly in RH; index and density by volume mixing with the table's water (the default)",
         "M. D. Petters and S. M. Kreidenweis, Atmos. Chem. Phys. 7, 1961-1971 (2007), eq. 11 without the Kelvin "
         "term"},
        {HumidityRule::linear, "linear",
         "the optical properties of the two neighbouring tabulated humidities, interpolated linearly in RH (an "
         "external mixture of the two states)",
         "OPAC tabulates 0, 50, 70, 80, 90, 95, 98, 99 % (Hess et al. 1998)"},
        {HumidityRule::nearest, "nearest", "the nearest tabulated humidity (libRadtran's choice)",
         "libRadtran 2.0, src/cloud.c, aer_ssprop2optprop"},
    };
    detail::check_enum_order(t, &HumidityRuleInfo::id);
    return t;
  }();
  return rows;
}

const HumidityRuleInfo& info(HumidityRule r) { return detail::row_of(humidity_rules(), r); }
const HumidityRuleInfo* find_humidity_rule(const std::string& name) { return detail::find_by_name(humidity_rules(), name); }
std::string to_string(HumidityRule r) { return info(r).name; }

}  // namespace attenuvis::weather
