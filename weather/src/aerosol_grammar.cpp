// Aerosols in the condition grammar: haze:TYPE:rh=RH[:OPTIONS] and
// aerosol:COMP=N[,COMP=N...]:rh=RH[:OPTIONS] (condition_grammar.hpp; the
// names come from the registries of aerosol.hpp).
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "attenuvis/weather/aerosol.hpp"
#include "condition_fields.hpp"
#include "registry_rows.hpp"

namespace attenuvis::weather::detail {
namespace {

std::string rule_alternatives() {
  std::string out;
  for (const auto& r : humidity_rules()) out += (out.empty() ? "" : "|") + r.name;
  return out;
}

bool has_key(const std::string& field, const char* key) { return field.rfind(key, 0) == 0; }

// The keys of the drops' options, which an aerosol does not take.
bool is_drop_option(const std::string& field) {
  for (const char* key : {"m=", "water=", "N=", "lwc=", "index="})
    if (has_key(field, key)) return true;
  return false;
}

// rh=, growth=, visibility=, mass= from field `from` on; rh= is required.
void read_options(AerosolCondition& c, const Fields& f, std::size_t from) {
  bool rh = false, growth = false;
  for (std::size_t i = from; i < f.size(); ++i) {
    const std::string& field = f[i];
    const auto once = [&](bool& seen, const char* key) {
      if (seen) f.fail(std::string(key) + " given twice");
      seen = true;
    };
    if (has_key(field, "rh=")) {
      once(rh, "rh=");
      c.relative_humidity_percent = f.keyed(i, 3, domain::relative_humidity);
    } else if (has_key(field, "growth=")) {
      once(growth, "growth=");
      const HumidityRuleInfo* rule = find_humidity_rule(field.substr(7));
      if (!rule) f.fail("growth '" + field.substr(7) + "' is not " + name_list(names_of(humidity_rules())));
      c.humidity_rule = rule->id;
    } else if (has_key(field, "visibility=") || has_key(field, "mass=")) {
      if (!std::holds_alternative<AsGiven>(c.scaling)) f.fail("give visibility= or mass= once, not both");
      if (has_key(field, "mass=")) c.scaling = ScaledToDryMass{f.keyed(i, 5, domain::aerosol_mass)};
      else c.scaling = ScaledToVisibility{f.distance(i, 11)};
    } else if (is_drop_option(field)) {
      f.fail("'" + field.substr(0, field.find('=') + 1) +
             "' is an option of drops: an aerosol's components carry their own indices and number densities "
             "(scale them with visibility= or mass=)");
    } else {
      f.fail("unexpected field '" + field + "' (an aerosol takes rh=, growth=, visibility=, mass=)");
    }
  }
  if (!rh) f.fail(f[0] + ":" + f[1] + " needs its relative humidity, :rh=0..99 (percent)");
}

}  // namespace

bool starts_with_component(const std::string& text, std::size_t at) {
  for (const auto& c : aerosol_components())
    if (text.compare(at, c.name.size() + 1, c.name + "=") == 0) return true;
  return false;
}

Condition parse_haze(const Fields& f) {
  f.require(2);
  const AerosolMixtureInfo* m = find_aerosol_mixture(f[1]);
  if (!m) f.fail("unknown aerosol type '" + f[1] + "' (" + aerosol_mixture_names() + ")");
  AerosolCondition c;
  c.mixture = m->id;
  c.amounts = m->amounts;
  read_options(c, f, 2);
  return c;
}

Condition parse_aerosol(const Fields& f) {
  f.require(2);
  AerosolCondition c;
  std::size_t start = 0;
  const std::string& list = f[1];
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    const std::string name = item.substr(0, eq);
    const AerosolComponentInfo* ci = find_aerosol_component(name);
    if (!ci) f.fail("unknown aerosol component '" + name + "' (" + aerosol_component_names() + ")");
    if (eq == std::string::npos) f.fail("component " + name + " needs its number density, " + name + "=PER_CM3");
    for (const AerosolAmount& a : c.amounts)
      if (a.component == ci->id) f.fail("component " + name + " given twice");
    c.amounts.push_back({ci->id, f.in(domain::number_density, item.substr(eq + 1))});
    start = comma + 1;
  }
  read_options(c, f, 2);
  return c;
}

std::string aerosol_text(const AerosolCondition& c) {
  using io::shortest;
  std::string out;
  if (c.mixture) {
    out = "haze:" + to_string(*c.mixture);
  } else {
    out = "aerosol:";
    for (std::size_t i = 0; i < c.amounts.size(); ++i)
      out += (i ? "," : "") + to_string(c.amounts[i].component) + "=" + shortest(c.amounts[i].per_cm3);
  }
  out += ":rh=" + shortest(c.relative_humidity_percent);
  if (c.humidity_rule != humidity_rules().front().id) out += ":growth=" + to_string(c.humidity_rule);
  if (const auto* v = std::get_if<ScaledToVisibility>(&c.scaling)) out += ":visibility=" + shortest(v->visibility_m) + "m";
  if (const auto* m = std::get_if<ScaledToDryMass>(&c.scaling)) out += ":mass=" + shortest(m->ug_per_m3);
  return out;
}

std::vector<std::pair<std::string, std::string>> aerosol_option_help() {
  return {
      {":growth=" + rule_alternatives(),
       "between OPAC's humidities (0 50 70 80 90 95 98 99 %): " + humidity_rules().front().name +
           " (default, kappa-Koehler fitted to the table), linear (in RH), nearest (libRadtran)"},
      {":visibility=DIST", "scale the number densities to this visibility at 550 nm (Koschmieder, --threshold)"},
      {":mass=UG_M3", "scale the number densities to this dry mass concentration (ug/m^3)"},
  };
}

}  // namespace attenuvis::weather::detail
