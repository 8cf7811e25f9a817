// Aerosols as conditions (condition.hpp: AerosolCondition): the registries the
// grammar reads, haze:TYPE and aerosol:COMP=N,..., sweeps over humidity, the
// scalings, and the errors for bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "../cli_run.hpp"
#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

AerosolCondition aerosol(const std::string& text) { return std::get<AerosolCondition>(parse_condition(text)); }

std::string parse_error(const std::string& text) {
  try {
    parse_condition(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("aerosol conditions: every OPAC type and component parses and reads back", "[weather][aerosol]") {
  for (const AerosolMixtureInfo& m : aerosol_mixtures()) {
    const std::string text = "haze:" + m.name + ":rh=80";
    const AerosolCondition c = aerosol(text);
    CHECK(c.mixture == m.id);
    CHECK(c.amounts.size() == m.amounts.size());
    CHECK(to_text(c) == text);
    CHECK_THAT(condition_grammar(), Contains(m.name));
  }
  for (const AerosolComponentInfo& ci : aerosol_components()) {
    const std::string text = "aerosol:" + ci.name + "=12.5:rh=0";
    CHECK(to_text(aerosol(text)) == text);
    CHECK_THAT(condition_grammar(), Contains(ci.name));
  }
  for (const HumidityRuleInfo& r : humidity_rules()) CHECK(aerosol("haze:urban:rh=85:growth=" + r.name).humidity_rule == r.id);
  // The OPAC program's own output for continental polluted (OPAC 3.1, opac_calc/copo): inso 0.6, waso 15700, soot 34300.
  const AerosolCondition copo = aerosol("haze:continental-polluted:rh=80");
  REQUIRE(copo.amounts.size() == 3);
  CHECK(copo.amounts[0].per_cm3 == 15700);
  CHECK(copo.amounts[1].per_cm3 == 0.6);
  CHECK(copo.amounts[2].per_cm3 == 34300);
}

TEST_CASE("aerosol conditions: a user's mixture, its options and their text", "[weather][aerosol]") {
  const AerosolCondition c = aerosol("aerosol:waso=7000,soot=8300,inso=0.4:rh=70:growth=linear:visibility=5km");
  REQUIRE(c.amounts.size() == 3);
  CHECK(c.amounts[1].component == AerosolComponent::soot);
  CHECK(c.amounts[1].per_cm3 == 8300);
  CHECK(c.relative_humidity_percent == 70);
  CHECK(c.humidity_rule == HumidityRule::linear);
  CHECK(std::get<ScaledToVisibility>(c.scaling).visibility_m == 5000);
  CHECK(to_text(c) == "aerosol:waso=7000,soot=8300,inso=0.4:rh=70:growth=linear:visibility=5000m");
  CHECK(std::get<ScaledToDryMass>(aerosol("haze:desert:rh=50:mass=120").scaling).ug_per_m3 == 120);
  // In a list the commas of a mixture stay inside it.
  CHECK(split_condition_list("clear,aerosol:waso=7000,soot=8300:rh=50,rain:8") ==
        std::vector<std::string>{"clear", "aerosol:waso=7000,soot=8300:rh=50", "rain:8"});
  CHECK(needs_mie(parse_condition("haze:urban:rh=0")));
}

TEST_CASE("aerosol conditions: a humidity sweep in a table", "[weather][aerosol]") {
  const auto rows = expand_conditions("haze:urban:rh=0..99/20");
  REQUIRE(rows.size() == 6);
  CHECK(rows[1].label == "haze:urban:rh=20");
  CHECK(rows.back().label == "haze:urban:rh=99");
  CHECK(std::get<AerosolCondition>(rows.back().condition).relative_humidity_percent == 99);
  const auto vis = expand_conditions("haze:urban:rh=50:visibility=2..6/2km");
  REQUIRE(vis.size() == 3);
  CHECK(std::get<ScaledToVisibility>(std::get<AerosolCondition>(vis[2].condition).scaling).visibility_m == 6000);
}

TEST_CASE("aerosol conditions: bad input names the value and the range", "[weather][aerosol]") {
  CHECK_THAT(parse_error("aerosol:wasp=7000:rh=50"), Contains("unknown aerosol component 'wasp'") && Contains("waso"));
  CHECK_THAT(parse_error("haze:suburban:rh=50"), Contains("unknown aerosol type 'suburban'") && Contains("urban"));
  CHECK_THAT(parse_error("haze:urban:rh=100"), Contains("relative humidity RH '100'") && Contains("[0, 99] %"));
  CHECK_THAT(parse_error("haze:urban:rh=-5"), Contains("-5") && Contains("[0, 99] %"));
  CHECK_THAT(parse_error("aerosol:waso=-7000:rh=50"), Contains("number density N '-7000'") && Contains("cm^-3"));
  CHECK_THAT(parse_error("aerosol:waso=7000,soot=-1:rh=50"), Contains("-1") && Contains("cm^-3"));
  CHECK_THAT(parse_error("aerosol:waso:rh=50"), Contains("waso=PER_CM3"));
  CHECK_THAT(parse_error("aerosol:waso=1,waso=2:rh=50"), Contains("given twice"));
  CHECK_THAT(parse_error("haze:urban"), Contains("needs its relative humidity"));
  CHECK_THAT(parse_error("haze:urban:rh=50:rh=60"), Contains("rh= given twice"));
  CHECK_THAT(parse_error("haze:urban:rh=50:growth=hanel"), Contains("growth 'hanel'") && Contains("kappa"));
  CHECK_THAT(parse_error("haze:urban:rh=50:visibility=5km:mass=3"), Contains("not both"));
  CHECK_THAT(parse_error("haze:urban:rh=50:m=1.5"), Contains("option of drops"));
  CHECK_THAT(parse_error("haze:urban:rh=50:mass=0"), Contains("aerosol dry mass concentration"));
  // A sweep only where a number may sweep: a component's number density is read as text.
  CHECK_THROWS_WITH(expand_conditions("aerosol:waso=1..5:rh=50"), Contains("'1..5' is not a number"));
}

TEST_CASE("aerosol conditions: index= gives any Mie condition a file's index", "[weather][aerosol][index]") {
  const std::string file = std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/index/H2O-Hale.yml";
  const auto c = std::get<MieCondition>(parse_condition("drops:lognormal:r=2um:sg=1.5:N=100:index=" + file));
  CHECK(std::get<IndexFile>(c.index).path == file);
  CHECK(to_text(c) == "drops:lognormal:r=2e-06m:sg=1.5:index=" + file + ":N=100");
  // The same drops with the water table itself: the same index, so the same sigma.
  Settings s;
  const auto table = parse_condition("drops:lognormal:r=2um:sg=1.5:N=100:water=hale-querry");
  CHECK(sigma(c, 550e-9, s).per_m == Approx(sigma(table, 550e-9, s).per_m).epsilon(1e-12));
  CHECK_THAT(sigma(c, 550e-9, s).note, Contains("H2O-Hale.yml") && Contains("Hale"));
  // A path with ':' runs up to the next option.
  const auto colon = std::get<MieCondition>(parse_condition("fog:advection:index=/tmp/a:b.yml:N=10"));
  CHECK(std::get<IndexFile>(colon.index).path == "/tmp/a:b.yml");
  CHECK_THROWS_WITH(sigma(colon, 550e-9, s), Contains("/tmp/a:b.yml"));
  CHECK_THROWS_WITH(sigma(c, 250e-6, s), Contains("H2O-Hale.yml") && Contains("250000 nm"));
}

TEST_CASE("aerosol conditions: sigma prints the Koschmieder visibility beside sigma", "[weather][aerosol][cli]") {
  const auto r = cli_run::run("sigma haze:urban:rh=95 --json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.output);
  const double sigma = j[0]["sigma"], vis = j[0]["visibility_m"];
  CHECK(vis == Approx(-std::log(0.02) / sigma).epsilon(1e-12));
  const auto text = cli_run::run("sigma haze:urban:rh=95");
  CHECK_THAT(text.output, Contains("visibility") && Contains("OPAC urban aerosol at 95 % RH"));
  const auto bad = cli_run::run("sigma haze:urban:rh=99.5");
  CHECK(bad.status != 0);
  CHECK_THAT(bad.output, Contains("attenuvis: error:") && Contains("99.5"));
}
