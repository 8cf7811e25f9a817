// A weather condition as a typed value: one of a closed set of kinds, each
// with its parameters as numbers and enums.  Text enters only through the
// grammar (condition_grammar.hpp: parse_condition, expand_conditions); code
// that needs a condition builds it directly:
//
//   Condition rain = RainPowerLaw{8.0, RainLaw::seed};
//   Condition fog  = MieCondition{FogPreset::advection, ConstantIndex{{1.33, 0.0}}, {}, {}};
//   Condition haze = AerosolCondition{AerosolMixture::urban, info(AerosolMixture::urban).amounts, 80.0};
//
// sigma.hpp computes the extinction coefficient of any of them.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "attenuvis/weather/aerosol.hpp"
#include "attenuvis/weather/empirical_models.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// Clear air: the seed paper's sigma = 0.00015 1/m (Sec. Results), or
// Koschmieder at Settings::contrast_threshold from a visibility.
struct ClearAir {
  std::optional<double> visibility_m;
};
// Any atmosphere of a given visibility (Koschmieder).
struct Visibility {
  double visibility_m = 0;
};
// A sigma given by the user, in 1/m.
struct GivenSigma {
  double per_m = 0;
};
// P.1817-1-style rain power law, read per Settings::convention.
struct RainPowerLaw {
  double rate_mm_h = 0;
  RainLaw law = RainLaw::seed;
};
// P.1817-1 snow a(lambda) S^b, read per Settings::convention.
struct Snow {
  SnowType type = SnowType::dry;
  double rate_mm_h = 0;
};
// Empirical fog models from a visibility (Kruse, Kim, Al Naboulsi).
struct FogFromVisibility {
  VisibilityFogModel model = VisibilityFogModel::kim;
  double visibility_m = 0;
};

// ---- Mie over a size distribution -------------------------------------------
// The drops: Marshall-Palmer rain, a P.1817-1 / seed fog preset (FogPreset,
// size_distribution.hpp), a file (distribution_file.hpp), or a parametric
// distribution.
struct MarshallPalmerRain {
  double rate_mm_h = 0;
};
struct DistributionFile {
  std::string path;
};
// A parametric distribution with the user's parameters (grammar: drops:FAMILY:...).
// Those without an amount of their own (log-normal, gamma, power law) hold one
// particle per cm^3 and are scaled by the condition's N= or lwc= (required).
struct LogNormalDrops {   // n ~ exp(-(ln r - ln r_m)^2 / (2 ln^2 sg)) / r
  double median_radius_m = 0, sigma_g = 0;
};
struct GammaDrops {       // n ~ r^alpha exp(-alpha r / r_mode)
  double mode_radius_m = 0, alpha = 0;
};
struct ModifiedGammaDrops {  // n = a r^alpha exp(-b r^gamma), r in um, n in cm^-3 um^-1 (Deirmendjian 1969)
  double a = 0, alpha = 0, b = 0, gamma = 1;
};
struct ExponentialDrops { // N(D) = N0 exp(-Lambda D), N0 in m^-3 mm^-1, Lambda in mm^-1, D the diameter
  double n0_per_m3_per_mm = 0, lambda_per_mm = 0;
};
struct PowerLawDrops {    // n ~ r^-nu on [r_min, r_max] (Junge)
  double nu = 0, r_min_m = 0, r_max_m = 0;
};
struct ParametricDrops {
  std::variant<LogNormalDrops, GammaDrops, ModifiedGammaDrops, ExponentialDrops, PowerLawDrops> family;
};
// True for the families that need N= or lwc= to fix their amount.
bool needs_amount(const ParametricDrops& d);

// The drops of a Mie condition: one of the kinds above.
using Drops = std::variant<MarshallPalmerRain, FogPreset, DistributionFile, ParametricDrops>;

// The refractive index: Settings::water_table, a named table (WaterTable,
// refractive_index.hpp: water or ice), a constant, or a file
// (index_file.hpp: refractiveindex.info YAML or three columns).
struct SettingsWaterTable {};
struct ConstantIndex {
  std::complex<double> m;  // n + i k, k >= 0
};
struct IndexFile {
  std::string path;
};
using IndexSource = std::variant<SettingsWaterTable, WaterTable, ConstantIndex, IndexFile>;

// Rescaling of the drops before integrating: as given, to a number density,
// or to a liquid water content.
struct AsGiven {};
struct NumberDensity {
  double per_cm3 = 0;
};
struct LiquidWaterContent {
  double g_per_m3 = 0;
};
using Rescaling = std::variant<AsGiven, NumberDensity, LiquidWaterContent>;

// Core–shell particles (coated_optics.hpp): the drops' radii are the cores'
// (their index `index` above), each under a shell of this index that makes up
// this fraction of the particle's volume (outer radius r (1 − f)^(−1/3)).
struct Coating {
  double shell_volume_fraction = 0;  // in [0, 0.999]
  std::complex<double> shell_m;      // n + i k, k >= 0
};

// A condition whose sigma is Mie scattering over a size distribution of drops.
struct MieCondition {
  Drops drops;
  IndexSource index;
  Rescaling rescaling;
  std::optional<Coating> coating = std::nullopt;  // homogeneous drops when empty
};

// ---- Aerosols (aerosol.hpp) ---------------------------------------------------
// An external mixture of OPAC components at a relative humidity: an OPAC type
// (haze:urban) or the user's own (aerosol:waso=7000,soot=8300).  The number
// densities may be scaled before integrating so that the Koschmieder
// visibility at 550 nm is a given one, or to a dry mass concentration.
struct ScaledToVisibility {
  double visibility_m = 0;  // -ln(Settings::contrast_threshold) / sigma_ext(550 nm)
};
struct ScaledToDryMass {
  double ug_per_m3 = 0;  // sum of N_i rho_i 4/3 pi <r^3>_i of the dry components, within their cut-offs
};
using AerosolScaling = std::variant<AsGiven, ScaledToVisibility, ScaledToDryMass>;

// An aerosol condition: the amounts of its components, the humidity, the
// growth rule and the scaling.
struct AerosolCondition {
  std::optional<AerosolMixture> mixture;  // the OPAC type the amounts are; none: the user's own
  std::vector<AerosolAmount> amounts;     // each component once
  double relative_humidity_percent = 0;   // [0, 99]
  HumidityRule humidity_rule = HumidityRule::kappa;
  AerosolScaling scaling = AsGiven{};
};

// A weather condition, as the grammar (condition_grammar.hpp) reads it.
using Condition = std::variant<ClearAir, Visibility, GivenSigma, RainPowerLaw, Snow, FogFromVisibility, MieCondition,
                               AerosolCondition>;

// A condition with the text it was written as (CSV columns and labels echo it).
struct LabelledCondition {
  std::string label;
  Condition condition;
};

// True for Mie conditions and aerosols: the conditions with particles, whose
// sigma is a Mie integral and which have every bulk quantity.
bool needs_mie(const Condition& c);
// True for the power laws, whose sigma depends on Settings::convention.
bool depends_on_convention(const Condition& c);

// Grammar text (condition_grammar.hpp) that parses back to the same
// condition, numbers in shortest round-trip form: for echoing conditions
// built in code.
std::string to_text(const Condition& c);

}  // namespace attenuvis::weather
