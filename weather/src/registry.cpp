// The registries of names in one shape (registry.hpp).
#include "attenuvis/weather/registry.hpp"

#include <stdexcept>

#include "attenuvis/weather/empirical_models.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/size_distribution.hpp"
#include "attenuvis/weather/table_quantity.hpp"
#include "registry_rows.hpp"

namespace attenuvis::weather {
namespace {

using Entries = std::vector<RegistryEntry>;

Entries water_table_entries() {
  Entries out;
  for (const auto& t : water_tables())
    out.push_back({t.name, "", t.help, t.citation,
                   {{"aliases", t.aliases}, {"file", t.file}, {"substance", t.substance}, {"source", t.source}}});
  return out;
}

Entries fog_preset_entries() {
  Entries out;
  for (const auto& p : fog_presets())
    out.push_back({p.name, "r in um, n in cm^-3 um^-1", p.help + ": n = a r^alpha exp(-b r)", p.citation,
                   {{"a", p.a}, {"alpha", p.alpha}, {"b", p.b}}});
  return out;
}

Entries distribution_preset_entries() {
  Entries out;
  for (const auto& p : distribution_presets()) out.push_back({p.name, "", p.help, p.citation, {}});
  return out;
}

Entries rain_law_entries() {
  Entries out;
  for (const auto& l : rain_power_laws())
    out.push_back({l.name, "dB/km (P.1817-1), R in mm/h; read per the convention", "gamma = k R^alpha", l.source,
                   {{"k", l.k}, {"alpha", l.alpha}, {"default", l.law == rain_power_laws().front().law}}});
  return out;
}

Entries snow_type_entries() {
  Entries out;
  for (const auto& t : snow_types())
    out.push_back({t.name, "dB/km (P.1817-1), S in mm/h melted; read per the convention",
                   "gamma = a(lambda) S^b, a = a_per_nm lambda_nm + a_at_0nm", t.source,
                   {{"a_per_nm", t.a_per_nm}, {"a_at_0nm", t.a_at_0nm}, {"b", t.b}}});
  return out;
}

Entries visibility_fog_model_entries() {
  Entries out;
  for (const auto& m : visibility_fog_models())
    out.push_back({m.name, "1/m (V in m)", m.formula, m.source, {{"validity", m.validity}}});
  return out;
}

Entries table_quantity_entries() {
  Entries out;
  for (const auto& q : table_quantities())
    out.push_back({q.name, unit_text(q.kind, SigmaUnit::per_m), q.long_name, "",
                   {{"python_name", q.python_name},
                    {"long_name", q.long_name},
                    {"standard_name", q.standard_name},
                    {"comment", q.comment},
                    {"needs_size_distribution", q.needs_size_distribution}}});
  return out;
}

struct Kind {
  const char* name;
  Entries (*entries)();
};
const Kind kKinds[] = {
    {"water_tables", water_table_entries},
    {"fog_presets", fog_preset_entries},
    {"distribution_presets", distribution_preset_entries},
    {"rain_power_laws", rain_law_entries},
    {"snow_types", snow_type_entries},
    {"visibility_fog_models", visibility_fog_model_entries},
    {"table_quantities", table_quantity_entries},
};

}  // namespace

const std::vector<std::string>& registry_kinds() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& k : kKinds) out.push_back(k.name);
    return out;
  }();
  return names;
}

std::vector<RegistryEntry> registry(const std::string& kind) {
  for (const auto& k : kKinds)
    if (kind == k.name) return k.entries();
  throw std::invalid_argument("unknown kind of name '" + kind + "' (" + detail::name_list(registry_kinds()) + ")");
}

}  // namespace attenuvis::weather
