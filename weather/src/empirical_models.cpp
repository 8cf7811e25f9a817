// P.1817-1 power laws and visibility-based fog models.
#include "attenuvis/weather/empirical_models.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "registry_rows.hpp"

namespace attenuvis::weather {

using detail::check_enum_order;

const std::vector<RainLawCoefficients>& rain_power_laws() {
  static const std::vector<RainLawCoefficients> laws = [] {
    std::vector<RainLawCoefficients> l = {
        {RainLaw::seed, "seed", 1.17, 0.65, "seed paper (Schwartz et al. 2021), Sec. Rain: k=1.17, alpha=0.65"},
        {RainLaw::carbonneau, "carbonneau", 1.076, 0.67,
         "ITU-R P.1817-1 (Carbonneau et al. 1998): k=1.076, alpha=0.67"},
        {RainLaw::p1814, "p1814", 1.2924, 0.6436, "ITU-R P.1814-1 (mu=0): k=1.2924, alpha=0.6436"},
    };
    check_enum_order(l, &RainLawCoefficients::law);
    return l;
  }();
  return laws;
}

const RainLawCoefficients& rain_power_law(RainLaw law) { return detail::row_of(rain_power_laws(), law); }

const RainLawCoefficients& rain_power_law(const std::string& name) {
  std::string names;
  for (const auto& l : rain_power_laws()) {
    if (l.name == name) return l;
    names += (names.empty() ? "" : ", ") + l.name;
  }
  throw std::invalid_argument("unknown rain law '" + name + "' (" + names + ")");
}

std::string to_string(RainLaw law) { return rain_power_law(law).name; }

const std::vector<SnowTypeInfo>& snow_types() {
  static const std::string source = "ITU-R P.1817-1; seed paper (Schwartz et al. 2021), Table \"Wet and Dry Snow\"";
  static const std::vector<SnowTypeInfo> types = [] {
    std::vector<SnowTypeInfo> t = {
        {SnowType::wet, "wet", 0.0001023, 3.7855466, 0.72, source},
        {SnowType::dry, "dry", 0.0000542, 5.4958776, 1.38, source},
    };
    check_enum_order(t, &SnowTypeInfo::id);
    return t;
  }();
  return types;
}

const SnowTypeInfo& info(SnowType type) { return detail::row_of(snow_types(), type); }

const SnowTypeInfo* find_snow_type(const std::string& name) { return detail::find_by_name(snow_types(), name); }

std::string to_string(SnowType type) { return info(type).name; }

SnowCoefficients snow_coefficients(SnowType type, double wavelength_m) {
  double nm = wavelength_m * 1e9;
  const SnowTypeInfo& t = info(type);
  return {t.a_per_nm * nm + t.a_at_0nm, t.b};
}

double power_law_sigma_per_m(double value, Convention c) {
  return c == Convention::itu ? dB_per_km_to_per_m(value) : per_km_to_per_m(value);
}

const std::vector<VisibilityFogModelInfo>& visibility_fog_models() {
  static const std::vector<VisibilityFogModelInfo> models = [] {
    const std::string kruse_kim = "sigma = (3.912/V)(lambda/550 nm)^-q, q from V: ";
    const std::string naboulsi = "M. Al Naboulsi, H. Sizun and F. de Fornel, Opt. Eng. 43, 319 (2004)";
    const std::string naboulsi_validity = "690-1550 nm, V 50-1000 m";
    std::vector<VisibilityFogModelInfo> m = {
        {VisibilityFogModel::kruse, "kruse", kruse_kim + "1.6 for V > 50 km, 1.3 for 6-50 km, 0.585 V_km^(1/3) below",
         "400-1600 nm; not meant for fog (V < 6 km)",
         "P. W. Kruse, L. D. McGlauchlin and R. B. McQuistan, Elements of Infrared Technology, Wiley (1962)"},
        {VisibilityFogModel::kim, "kim",
         kruse_kim + "1.6 for V > 50 km, 1.3 for 6-50 km, 0.16 V_km + 0.34 for 1-6 km, V_km - 0.5 for 0.5-1 km, "
                     "0 below 0.5 km",
         "400-1600 nm", "I. I. Kim, B. McArthur and E. Korevaar, Proc. SPIE 4214, 26 (2001)"},
        {VisibilityFogModel::naboulsi_advection, "naboulsi-advection",
         "advection fog: sigma = (0.11478 lambda_um + 3.8367)/V_km 1/km", naboulsi_validity, naboulsi},
        {VisibilityFogModel::naboulsi_radiation, "naboulsi-radiation",
         "radiation fog: sigma = (0.18126 lambda_um^2 + 0.13709 lambda_um + 3.7502)/V_km 1/km", naboulsi_validity,
         naboulsi},
    };
    check_enum_order(m, &VisibilityFogModelInfo::id);
    return m;
  }();
  return models;
}

const VisibilityFogModelInfo& info(VisibilityFogModel m) { return detail::row_of(visibility_fog_models(), m); }

const VisibilityFogModelInfo* find_visibility_fog_model(const std::string& name) {
  return detail::find_by_name(visibility_fog_models(), name);
}

std::string to_string(VisibilityFogModel m) { return info(m).name; }

EmpiricalResult fog_from_visibility(VisibilityFogModel model, double visibility_m, double wavelength_m) {
  if (!(visibility_m > 0)) throw std::invalid_argument("visibility must be > 0");
  double v_km = visibility_m * 1e-3, nm = wavelength_m * 1e9, um = wavelength_m * 1e6;
  EmpiricalResult r;
  std::ostringstream warn;
  if (model == VisibilityFogModel::kruse || model == VisibilityFogModel::kim) {
    double q = 0;
    if (v_km > 50) q = 1.6;
    else if (v_km > 6) q = 1.3;
    else if (model == VisibilityFogModel::kruse) q = 0.585 * std::cbrt(v_km);
    else if (v_km > 1) q = 0.16 * v_km + 0.34;
    else if (v_km > 0.5) q = v_km - 0.5;
    else q = 0;
    r.sigma_per_m = 3.912 / visibility_m * std::pow(nm / 550.0, -q);
    if (model == VisibilityFogModel::kruse) {
      r.model = "Kruse et al. (1962): (3.912/V)(lambda/550nm)^-q, q=" + std::to_string(q);
      if (v_km < 6) warn << "Kruse's q is not meant for fog (V < 6 km; Kim et al. 2001); consider fog:kim. ";
    } else {
      r.model = "Kim et al. (2001): (3.912/V)(lambda/550nm)^-q, q=" + std::to_string(q);
    }
    if (nm < 400 || nm > 1600) warn << "wavelength " << nm << " nm is outside 400-1600 nm, where this model was fit. ";
  } else {
    double per_km = model == VisibilityFogModel::naboulsi_advection
                        ? (0.11478 * um + 3.8367) / v_km
                        : (0.18126 * um * um + 0.13709 * um + 3.7502) / v_km;
    r.sigma_per_m = per_km_to_per_m(per_km);
    r.model = model == VisibilityFogModel::naboulsi_advection
                  ? "Al Naboulsi et al. (2004) advection fog: (0.11478 lambda_um + 3.8367)/V_km 1/km"
                  : "Al Naboulsi et al. (2004) radiation fog: (0.18126 lambda_um^2 + 0.13709 lambda_um + 3.7502)/V_km 1/km";
    if (nm < 690 || nm > 1550) warn << "wavelength " << nm << " nm is outside the model's stated 690-1550 nm. ";
    if (visibility_m < 50 || visibility_m > 1000)
      warn << "visibility " << visibility_m << " m is outside fog visibilities 50-1000 m the model was fit for. ";
  }
  r.warning = warn.str();
  if (!r.warning.empty() && r.warning.back() == ' ') r.warning.pop_back();
  return r;
}

}  // namespace attenuvis::weather
