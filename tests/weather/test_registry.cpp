// The registries of names (registry.hpp): each name is read back by the
// grammar, the command line's help and the library's own lookups, and the
// uniform view lists what the typed tables hold.
#include <catch2/catch.hpp>

#include <string>
#include <variant>
#include <vector>

#include "../cli_run.hpp"
#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

template <class Rows>
std::vector<std::string> names_of(const Rows& rows) {
  std::vector<std::string> out;
  for (const auto& row : rows) out.push_back(row.name);
  return out;
}

std::vector<std::string> registry_names(const std::string& kind) {
  std::vector<std::string> out;
  for (const auto& e : registry(kind)) out.push_back(e.name);
  return out;
}

}  // namespace

TEST_CASE("the uniform view lists each typed registry", "[weather][registry]") {
  CHECK(registry_kinds() == std::vector<std::string>{"water_tables", "fog_presets", "distribution_presets",
                                                     "rain_power_laws", "snow_types", "visibility_fog_models",
                                                     "table_quantities"});
  CHECK(registry_names("water_tables") == names_of(water_tables()));
  CHECK(registry_names("fog_presets") == names_of(fog_presets()));
  CHECK(registry_names("distribution_presets") == names_of(distribution_presets()));
  CHECK(registry_names("rain_power_laws") == names_of(rain_power_laws()));
  CHECK(registry_names("snow_types") == names_of(snow_types()));
  CHECK(registry_names("visibility_fog_models") == names_of(visibility_fog_models()));
  CHECK(registry_names("table_quantities") == names_of(table_quantities()));
  for (const auto& kind : registry_kinds())
    for (const auto& e : registry(kind)) {
      INFO(kind << " " << e.name);
      CHECK(!e.help.empty());
    }
  const auto seed = registry("rain_power_laws").front();
  CHECK(std::get<double>(seed.details.at("k")) == 1.17);
  CHECK(std::get<bool>(seed.details.at("default")));
  CHECK_THROWS_WITH(registry("colours"), Contains("unknown kind of name 'colours'") && Contains("water_tables"));
}

TEST_CASE("every registry name reads back through its enum and the grammar", "[weather][registry]") {
  for (const auto& t : water_tables()) {
    CHECK(find_water_table(t.name) == &t);
    CHECK(to_string(t.id) == t.name);
    const auto c = std::get<MieCondition>(parse_condition("fog:advection:water=" + t.name));
    CHECK(std::get<WaterTable>(c.index) == t.id);
    for (const auto& alias : t.aliases) CHECK(find_water_table(alias) == &t);
  }
  for (const auto& p : fog_presets()) {
    CHECK(to_string(p.id) == p.name);
    CHECK(std::get<FogPreset>(std::get<MieCondition>(parse_condition("fog:" + p.name)).drops) == p.id);
  }
  for (const auto& l : rain_power_laws())
    CHECK(std::get<RainPowerLaw>(parse_condition("rain:8:" + l.name)).law == l.law);
  CHECK(std::get<RainPowerLaw>(parse_condition("rain:8")).law == rain_power_laws().front().law);
  for (const auto& s : snow_types()) {
    CHECK(to_string(s.id) == s.name);
    CHECK(std::get<Snow>(parse_condition("snow:" + s.name + ":2")).type == s.id);
  }
  for (const auto& m : visibility_fog_models()) {
    CHECK(to_string(m.id) == m.name);
    CHECK(std::get<FogFromVisibility>(parse_condition("fog:" + m.name + ":500m")).model == m.id);
  }
  for (const auto& p : distribution_presets()) {
    std::string name = p.name;
    if (name.size() > 2 && name.compare(name.size() - 2, 2, ":R") == 0) name.replace(name.size() - 1, 1, "2");
    CHECK(is_preset_distribution(name));
    CHECK(preset_distribution(name).moment(0) > 0);
  }
  for (const auto& q : table_quantities()) CHECK(parse_quantity_list(q.name) == std::vector<Quantity>{q.id});
}

TEST_CASE("a water table's registry entry is its file's", "[weather][registry]") {
  for (const auto& t : water_tables()) {
    INFO(t.name);
    const RefractiveIndexTable& table = refractive_index_table(t.name);
    CHECK(table.name() == t.file);
    CHECK(table.citation() == t.citation);
    CHECK(&refractive_index_table(t.file) == &table);
  }
}

TEST_CASE("the grammar and the command line's help name every registry name", "[weather][registry][cli]") {
  const std::string& grammar = condition_grammar();
  for (const auto& names : {names_of(water_tables()), names_of(fog_presets()), names_of(rain_power_laws()),
                            names_of(snow_types()), names_of(visibility_fog_models())})
    for (const auto& name : names) CHECK_THAT(grammar, Contains(name));
  const auto sigma_help = cli_run::run("sigma --help");
  REQUIRE(sigma_help.status == 0);
  for (const auto& t : water_tables()) CHECK_THAT(sigma_help.output, Contains(t.name));
  const auto table_help = cli_run::run("table --help");
  for (const auto& q : table_quantities()) CHECK_THAT(table_help.output, Contains(q.name));
  const auto distribution_help = cli_run::run("distribution --help");
  for (const auto& p : distribution_presets()) CHECK_THAT(distribution_help.output, Contains(p.name));
}
