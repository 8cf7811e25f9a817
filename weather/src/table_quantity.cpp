// The registry of table quantities and the parameter of each condition.
#include "attenuvis/weather/table_quantity.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "registry_rows.hpp"

namespace attenuvis::weather {

const std::vector<QuantityInfo>& table_quantities() {
  // CF (Standard Name Table) names the particle coefficients only for aerosol,
  // volume_{extinction,scattering,absorption}_coefficient_in_air_due_to_ambient_aerosol_particles,
  // and defines "aerosol" as suspended particles "except cloud droplets": fog drops are cloud
  // droplets and rain and snow are precipitation, so those names would misdescribe every Mie
  // condition here.  CF has no name for a hydrometeor's coefficient, the bulk albedo or the
  // asymmetry parameter; the quantities carry long names and no standard name.
  static const std::string no_cf_name =
      "no CF standard_name: CF's volume_*_coefficient_in_air_due_to_ambient_aerosol_particles exclude cloud "
      "droplets, and fog, rain and snow are hydrometeors";
  static const std::vector<QuantityInfo> table = [] {
    std::vector<QuantityInfo> t = {
        {Quantity::sigma_ext, "sigma_ext", "sigma", QuantityKind::coefficient, "volume extinction coefficient", "",
         no_cf_name, false},
        {Quantity::sigma_sca, "sigma_sca", "scattering", QuantityKind::coefficient, "volume scattering coefficient",
         "", no_cf_name, true},
        {Quantity::sigma_abs, "sigma_abs", "absorption", QuantityKind::coefficient, "volume absorption coefficient",
         "", no_cf_name, true},
        {Quantity::ssa, "ssa", "albedo", QuantityKind::dimensionless, "single-scattering albedo sigma_sca/sigma_ext",
         "", "", true},
        {Quantity::g, "g", "asymmetry", QuantityKind::dimensionless,
         "asymmetry parameter <cos theta>, scattering-weighted", "", "", true},
        {Quantity::backscatter, "backscatter", "backscatter", QuantityKind::coefficient_per_sr,
         "volume backscatter coefficient beta_pi = integral of (Q_back/4 pi) pi r^2 n(r) dr", "",
         "no CF standard_name: CF's volume_attenuated_backwards_scattering_function_in_air includes attenuation on "
         "the way; this is the unattenuated coefficient of the drops",
         true},
        {Quantity::lidar_ratio, "lidar_ratio", "lidar_ratio", QuantityKind::steradian,
         "lidar (extinction-to-backscatter) ratio sigma_ext/beta_pi", "", "", true},
    };
    detail::check_enum_order(t, &QuantityInfo::id);
    return t;
  }();
  return table;
}

const QuantityInfo& info(Quantity q) { return detail::row_of(table_quantities(), q); }

std::string quantity_names() {
  std::string out;
  for (const auto& q : table_quantities()) out += (out.empty() ? "" : ", ") + q.name;
  return out;
}

std::vector<Quantity> parse_quantity_list(const std::string& text) {
  std::vector<Quantity> out;
  std::stringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) continue;
    const auto& all = table_quantities();
    const auto it = std::find_if(all.begin(), all.end(), [&](const QuantityInfo& q) { return q.name == name; });
    if (it == all.end())
      throw std::invalid_argument("unknown quantity '" + name + "' (known: " + quantity_names() + ")");
    if (std::find(out.begin(), out.end(), it->id) != out.end())
      throw std::invalid_argument("quantity '" + name + "' is listed twice");
    out.push_back(it->id);
  }
  if (out.empty()) throw std::invalid_argument("no quantities in '" + text + "' (known: " + quantity_names() + ")");
  return out;
}

namespace {
// The length unit of a per-steradian coefficient in a table of `unit`.
bool per_km(SigmaUnit unit) { return unit != SigmaUnit::per_m; }
}  // namespace

QuantityRequest parse_quantity_request(const std::string& text) {
  QuantityRequest out;
  std::string rest;
  std::stringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name == "phase") {
      if (out.phase) throw std::invalid_argument("'phase' is listed twice");
      out.phase = true;
      continue;
    }
    if (name.rfind("moments:", 0) != 0) {
      rest += (rest.empty() ? "" : ",") + name;
      continue;
    }
    if (out.max_moment >= 0) throw std::invalid_argument("'moments:L' is listed twice");
    const std::string l = name.substr(8);
    std::size_t used = 0;
    int value = -1;
    try {
      value = std::stoi(l, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (l.empty() || used != l.size() || value < 0 || value > kMaxTableMoment)
      throw std::invalid_argument("'" + name + "': L must be a whole number in [0, " +
                                  std::to_string(kMaxTableMoment) + "]");
    out.max_moment = value;
  }
  if (!rest.empty() || (out.max_moment < 0 && !out.phase)) {
    try {
      out.quantities = parse_quantity_list(rest);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      if (what.rfind("quantity '", 0) == 0) throw;  // listed twice: the known names would not help
      throw std::invalid_argument(what + "; besides them moments:L (Legendre moments chi_0..chi_L) and phase "
                                         "(the phase function on an angle grid)");
    }
  }
  return out;
}

std::string unit_text(QuantityKind kind, SigmaUnit unit) {
  switch (kind) {
    case QuantityKind::coefficient: return to_string(unit);
    case QuantityKind::dimensionless: return "1";
    case QuantityKind::coefficient_per_sr: return per_km(unit) ? "1/(km sr)" : "1/(m sr)";
    case QuantityKind::steradian: return "sr";
  }
  return "";
}

std::optional<std::string> udunits_text(QuantityKind kind, SigmaUnit unit) {
  if (kind == QuantityKind::dimensionless) return "1";
  if (kind == QuantityKind::steradian) return "sr";
  if (kind == QuantityKind::coefficient_per_sr) return per_km(unit) ? "km-1 sr-1" : "m-1 sr-1";
  switch (unit) {
    case SigmaUnit::per_m: return "m-1";
    case SigmaUnit::per_km: return "km-1";
    case SigmaUnit::dB_per_km: return std::nullopt;
  }
  return std::nullopt;
}

std::string unit_suffix(SigmaUnit unit) {
  switch (unit) {
    case SigmaUnit::per_m: return "per_m";
    case SigmaUnit::per_km: return "per_km";
    case SigmaUnit::dB_per_km: return "dB_per_km";
  }
  return "";
}

std::string column_suffix(QuantityKind kind, SigmaUnit unit) {
  switch (kind) {
    case QuantityKind::coefficient: return "_" + unit_suffix(unit);
    case QuantityKind::coefficient_per_sr: return per_km(unit) ? "_per_km_sr" : "_per_m_sr";
    case QuantityKind::steradian: return "_sr";
    case QuantityKind::dimensionless: return "";
  }
  return "";
}

double in_table_unit(QuantityKind kind, double value, SigmaUnit unit) {
  if (!std::isfinite(value)) return value;
  switch (kind) {
    case QuantityKind::coefficient: return convert_from_per_m(value, unit);
    case QuantityKind::coefficient_per_sr: return per_km(unit) ? value * 1e3 : value;
    case QuantityKind::dimensionless:
    case QuantityKind::steradian: return value;
  }
  return value;
}

std::optional<ConditionParameter> condition_parameter(const Condition& condition) {
  struct Visitor {
    std::optional<ConditionParameter> operator()(const ClearAir& c) const {
      if (c.visibility_m) return ConditionParameter{ParameterKind::visibility, *c.visibility_m};
      return std::nullopt;
    }
    std::optional<ConditionParameter> operator()(const Visibility& c) const {
      return ConditionParameter{ParameterKind::visibility, c.visibility_m};
    }
    std::optional<ConditionParameter> operator()(const GivenSigma& c) const {
      return ConditionParameter{ParameterKind::given_sigma, c.per_m};
    }
    std::optional<ConditionParameter> operator()(const RainPowerLaw& c) const {
      return ConditionParameter{ParameterKind::rate, c.rate_mm_h};
    }
    std::optional<ConditionParameter> operator()(const Snow& c) const {
      return ConditionParameter{ParameterKind::rate, c.rate_mm_h};
    }
    std::optional<ConditionParameter> operator()(const FogFromVisibility& c) const {
      return ConditionParameter{ParameterKind::visibility, c.visibility_m};
    }
    std::optional<ConditionParameter> operator()(const MieCondition& c) const {
      if (const auto* rain = std::get_if<MarshallPalmerRain>(&c.drops))
        return ConditionParameter{ParameterKind::rate, rain->rate_mm_h};
      return std::nullopt;
    }
  };
  return std::visit(Visitor{}, condition);
}

const ParameterInfo& info(ParameterKind k) {
  // lwe_precipitation_rate: CF's liquid-water-equivalent precipitation rate (canonical m s-1), which is what
  // the rain and snow rates of ITU-R P.1817-1 and of Marshall-Palmer are; visibility_in_air (m): CF's name.
  static const std::vector<ParameterInfo> table = [] {
    std::vector<ParameterInfo> t = {
        {ParameterKind::rate, "rate", "precipitation rate (liquid water equivalent)", "lwe_precipitation_rate",
         "mm/h", "mm h-1"},
        {ParameterKind::visibility, "visibility", "visibility the condition is set by", "visibility_in_air", "m", "m"},
        {ParameterKind::given_sigma, "given_sigma", "extinction coefficient given by the condition", "", "", ""},
    };
    detail::check_enum_order(t, &ParameterInfo::kind);
    return t;
  }();
  return table.at(static_cast<std::size_t>(k));
}

}  // namespace attenuvis::weather
