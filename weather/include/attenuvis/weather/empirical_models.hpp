// Closed-form attenuation models: ITU-R P.1817-1 rain and snow power laws and
// the visibility-based fog models (Kruse, Kim, Al Naboulsi).
//
// The power laws give a value in the Recommendation's unit, dB/km.  Which unit
// the value is read in is the Convention (units.hpp): itu reads dB/km, seed
// reads 1/km as the seed paper does.
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather {

// Each kind of model below is listed once, in a table the condition grammar,
// the command line's help and the Python layer read (names, coefficients,
// sources); registry.hpp shows them all in one shape.

// The rain power laws gamma = k R^alpha (R in mm/h):
//   seed        k=1.17,   alpha=0.65    seed paper Sec. Rain (the default)
//   carbonneau  k=1.076,  alpha=0.67    ITU-R P.1817-1, after Carbonneau et al. (1998)
//   p1814       k=1.2924, alpha=0.6436  ITU-R P.1814-1 with mu = 0
enum class RainLaw { seed, carbonneau, p1814 };
struct RainLawCoefficients {
  RainLaw law;
  std::string name;  // as the condition grammar spells it
  double k, alpha;
  std::string source;
};
// Every law, in the order of the enum (the first, seed, is the default).
const std::vector<RainLawCoefficients>& rain_power_laws();
const RainLawCoefficients& rain_power_law(RainLaw law);
// By grammar name; throws std::invalid_argument listing the names.
const RainLawCoefficients& rain_power_law(const std::string& name);
std::string to_string(RainLaw law);

// a(lambda) S^b, S in mm/h (P.1817-1; seed Table "Wet and Dry Snow"):
//   wet a = 0.0001023 lambda_nm + 3.7855466, b = 0.72
//   dry a = 0.0000542 lambda_nm + 5.4958776, b = 1.38
enum class SnowType { wet, dry };
struct SnowTypeInfo {
  SnowType id;
  std::string name;  // as the condition grammar spells it: "wet"
  double a_per_nm, a_at_0nm, b;  // a = a_per_nm lambda_nm + a_at_0nm
  std::string source;
};
// Every type, in the order of the enum.
const std::vector<SnowTypeInfo>& snow_types();
const SnowTypeInfo& info(SnowType type);
const SnowTypeInfo* find_snow_type(const std::string& name);  // nullptr for any other name
std::string to_string(SnowType type);                          // "wet" | "dry"
struct SnowCoefficients { double a, b; };
SnowCoefficients snow_coefficients(SnowType type, double wavelength_m);

// A power-law value (dB/km as published) read under `c`, in 1/m.
double power_law_sigma_per_m(double published_value, Convention c);

// The empirical fog models from a visibility V (fog_from_visibility below).
enum class VisibilityFogModel { kruse, kim, naboulsi_advection, naboulsi_radiation };
struct VisibilityFogModelInfo {
  VisibilityFogModel id;
  std::string name;      // as the condition grammar spells it: "naboulsi-advection"
  std::string formula;   // sigma from V and lambda, in words
  std::string validity;  // the range the model was stated or fit for
  std::string source;
};
// Every model, in the order of the enum.
const std::vector<VisibilityFogModelInfo>& visibility_fog_models();
const VisibilityFogModelInfo& info(VisibilityFogModel m);
const VisibilityFogModelInfo* find_visibility_fog_model(const std::string& name);  // nullptr for any other name
std::string to_string(VisibilityFogModel m);  // its name

// sigma of an empirical model and the formula it came from.
struct EmpiricalResult {
  double sigma_per_m = 0;
  std::string model;    // formula and source
  std::string warning;  // non-empty when outside the model's stated validity
};
// Kruse et al. (1962) and Kim et al. (2001): sigma = (3.912 / V) (lambda / 550 nm)^-q, with q
// from V (Kruse: 1.6 V > 50 km, 1.3 6-50 km, 0.585 V^1/3 below; Kim: 1.6, 1.3, 0.16 V + 0.34
// for 1-6 km, V - 0.5 for 0.5-1 km, 0 below 0.5 km).  The 3.912 is the 2 % threshold these
// models were defined with, independent of Settings::contrast_threshold.
// Al Naboulsi et al. (2004): advection (0.11478 lambda_um + 3.8367)/V,
// radiation (0.18126 lambda_um^2 + 0.13709 lambda_um + 3.7502)/V, 1/km with V in km,
// stated for 690-1550 nm; outside that range the result carries a warning.
EmpiricalResult fog_from_visibility(VisibilityFogModel model, double visibility_m, double wavelength_m);

// The seed paper's clear-air value (Sec. Results): 0.00015 1/m.
inline constexpr double kSeedClearSigmaPerM = 0.00015;

}  // namespace attenuvis::weather
