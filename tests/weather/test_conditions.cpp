// Condition grammar, closed-form weather models, units and conventions,
// against the seed paper and ITU-R P.1817-1 numbers.
#include <catch2/catch.hpp>

#include <cmath>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {
Settings seed_settings() {
  Settings s;
  s.convention = Convention::seed;
  return s;
}
}  // namespace

TEST_CASE("seed paper sigma values in the seed convention", "[weather][conditions][seed]") {
  // Seed paper, Sec. Results: rain 8 mm/h sigma = 0.0045, dry snow 4 mm/h sigma = 0.0374, clear 0.00015 (1/m).
  auto rain = sigma(parse_condition("rain:8"), 550e-9, seed_settings());
  CHECK(rain.per_m == Approx(0.0045).margin(0.00005));          // published to 2 significant digits
  CHECK(rain.per_m == Approx(1.17 * std::pow(8.0, 0.65) * 1e-3).epsilon(1e-14));
  CHECK(rain.convention == "seed");
  auto snow = sigma(parse_condition("snow:dry:4"), 550e-9, seed_settings());
  CHECK(snow.per_m == Approx(0.0374).margin(0.00005));
  // Seed Sec. Snow: at 550 nm, sigma = 0.0055256876 S^1.38 1/m.
  CHECK(snow.per_m == Approx(0.0055256876 * std::pow(4.0, 1.38)).epsilon(1e-12));
  CHECK(sigma(parse_condition("clear"), 550e-9, seed_settings()).per_m == 0.00015);
}

TEST_CASE("itu convention reads the P.1817 power laws as dB/km", "[weather][conditions]") {
  Settings itu;
  for (const char* c : {"rain:8", "rain:8:carbonneau", "rain:25:p1814", "snow:dry:4", "snow:wet:2"}) {
    INFO(c);
    auto a = sigma(parse_condition(c), 550e-9, itu), b = sigma(parse_condition(c), 550e-9, seed_settings());
    CHECK(b.per_m / a.per_m == Approx(10 * std::log10(std::exp(1.0))).epsilon(1e-14));  // 4.342944819
    CHECK(a.convention == "itu");
  }
  // P.1817-1 Carbonneau: 1.076 R^0.67 dB/km.
  CHECK(per_m_to_dB_per_km(sigma(parse_condition("rain:8:carbonneau"), 550e-9, itu).per_m) ==
        Approx(1.076 * std::pow(8.0, 0.67)).epsilon(1e-13));
  // Wet snow a(550 nm) = 0.0001023*550 + 3.7855466, b = 0.72 (seed Table tab:snow).
  CHECK(per_m_to_dB_per_km(sigma(parse_condition("snow:wet:2"), 550e-9, itu).per_m) ==
        Approx((0.0001023 * 550 + 3.7855466) * std::pow(2.0, 0.72)).epsilon(1e-13));
}

TEST_CASE("visibility, Koschmieder and contrast", "[weather][conditions][visibility]") {
  // ln(0.02) = -3.912 (seed Eq. koshmieder); ln(0.05) = -2.996 (meteorological optical range).
  CHECK(koschmieder_visibility_m(0.00015) == Approx(3.912023005 / 0.00015).epsilon(1e-9));
  CHECK(koschmieder_visibility_m(0.001, 0.05) == Approx(2995.732274).epsilon(1e-9));
  CHECK(contrast_ratio(0.0045, 100) == Approx(std::exp(-0.45)));
  Settings s;
  CHECK(sigma(parse_condition("visibility:2km"), 550e-9, s).per_m == Approx(3.912023005 / 2000).epsilon(1e-9));
  s.contrast_threshold = 0.05;
  CHECK(sigma(parse_condition("clear:10km"), 550e-9, s).per_m == Approx(2.995732274 / 10000).epsilon(1e-9));
  CHECK(sigma(parse_condition("sigma:3dB/km"), 550e-9, s).per_m == Approx(3 / 4342.944819032518).epsilon(1e-14));
  CHECK(sigma(parse_condition("sigma:2/km"), 550e-9, s).per_m == Approx(0.002));
}

TEST_CASE("empirical fog models", "[weather][conditions][fog]") {
  Settings s;
  // Kim et al. (2001): q = 0 below 500 m, so sigma = 3.912/V at any wavelength.
  CHECK(sigma(parse_condition("fog:kim:400m"), 550e-9, s).per_m == Approx(3.912 / 400));
  // Kim, V = 2 km: q = 0.16*2 + 0.34 = 0.66.
  CHECK(sigma(parse_condition("fog:kim:2km"), 1550e-9, s).per_m ==
        Approx(3.912 / 2000 * std::pow(1550 / 550.0, -0.66)));
  // Al Naboulsi advection at 1.55 um, V = 0.5 km: (0.11478*1.55 + 3.8367)/0.5 1/km.
  CHECK(sigma(parse_condition("fog:naboulsi-advection:500m"), 1550e-9, s).per_m ==
        Approx((0.11478 * 1.55 + 3.8367) / 0.5 * 1e-3));
  auto out_of_range = sigma(parse_condition("fog:naboulsi-radiation:500m"), 550e-9, s);
  CHECK_THAT(out_of_range.note, Contains("690-1550"));
  CHECK_THAT(sigma(parse_condition("fog:kruse:1km"), 550e-9, s).note, Contains("Kim"));
}

TEST_CASE("bad conditions show the grammar", "[weather][conditions][grammar]") {
  for (const char* bad : {"", "hail:3", "rain", "rain:-1", "rain:8:foo", "snow:4", "snow:slush:4", "fog:thick",
                          "sigma:abc", "visibility:2parsecs", "fog:advection:m=1.33-0.1i", "rain:1..10",
                          "fog:advection:N=1:lwc=1", "clear:1:2"}) {
    INFO(bad);
    CHECK_THROWS_WITH(parse_condition(bad), Contains("bad condition") && Contains("rain:RATE"));
  }
}

TEST_CASE("parsed forms and sweeps", "[weather][conditions][grammar]") {
  const auto c = parse_condition("fog:advection:m=1.33+1e-8i:N=50");
  const auto* mie = std::get_if<MieCondition>(&c);
  REQUIRE(mie);
  CHECK(std::get<FogPreset>(mie->drops) == FogPreset::advection);
  CHECK(std::get<ConstantIndex>(mie->index).m.imag() == 1e-8);
  CHECK(std::get<NumberDensity>(mie->rescaling).per_cm3 == 50);
  const auto file = std::get<MieCondition>(parse_condition("fog:file=/tmp/a:b.csv:water=segelstein"));
  CHECK(std::get<DistributionFile>(file.drops).path == "/tmp/a:b.csv");
  CHECK(std::get<WaterTable>(file.index) == WaterTable::segelstein);
  CHECK(!needs_mie(parse_condition("rain:8")));
  CHECK(needs_mie(parse_condition("rain:8:mie")));
  auto sweep = expand_conditions("rain:1..100");
  CHECK(sweep.size() == 100);
  CHECK(std::get<RainPowerLaw>(sweep.back().condition).rate_mm_h == 100);
  auto snow = expand_conditions("snow:dry:0.5..4/0.5");
  CHECK(snow.size() == 8);
  auto vis = expand_conditions("fog:kim:200..1000/200m");
  REQUIRE(vis.size() == 5);
  CHECK(std::get<FogFromVisibility>(vis[4].condition).visibility_m == 1000);
}

TEST_CASE("wavelength and unit parsing", "[weather][units]") {
  CHECK(parse_wavelength("550nm") == Approx(550e-9));
  CHECK(parse_wavelength("10.6um") == Approx(10.6e-6));
  CHECK_THROWS_WITH(parse_wavelength("550"), Contains("unit"));
  auto list = parse_wavelength_list("400:800:10nm");
  CHECK(list.size() == 41);
  CHECK(list.back() == Approx(800e-9));
  CHECK(parse_wavelength_list("380:780:5nm").size() == 81);
  CHECK(convert_from_per_m(1e-3, SigmaUnit::dB_per_km) == Approx(4.342944819));
}

TEST_CASE("power-law conditions do no Mie work", "[weather][conditions]") {
  // A constant index with an invalid (negative) n would make any Mie call throw;
  // power laws must not touch it.  Here: rain/snow succeed without data files.
  Settings s;
  s.water_table = "no-such-table";
  CHECK_NOTHROW(sigma(parse_condition("rain:8"), 550e-9, s));
  CHECK_NOTHROW(sigma(parse_condition("snow:wet:3"), 550e-9, s));
  CHECK_THROWS(sigma(parse_condition("fog:advection"), 550e-9, s));
}

TEST_CASE("the grammar help lists every kind and the units the parsers accept", "[weather][conditions][grammar]") {
  const std::string& g = condition_grammar();
  for (const char* line : {"clear | clear:DIST", "visibility:DIST", "sigma:VALUE[/m|/km|dB/km]", "rain:RATE:mie",
                           "rain:RATE[:seed|carbonneau|p1814]", "snow:wet:RATE | snow:dry:RATE", "fog:file=PATH",
                           "fog:kruse|kim|naboulsi-advection|naboulsi-radiation:DIST", ":m=N+Ki", ":water=", ":N=",
                           ":lwc=", "m, km or mi"}) {
    INFO(line);
    CHECK_THAT(g, Contains(line));
  }
  // The international mile (1609.344 m, NIST SP 811) is accepted, and the
  // message of a unit it does not know lists it.
  CHECK(std::get<Visibility>(parse_condition("visibility:1mi")).visibility_m == 1609.344);
  CHECK_THROWS_WITH(parse_condition("visibility:2parsecs"), Contains("m, km or mi"));
  CHECK_THROWS_WITH(parse_distance("2parsecs"), Contains("m, km or mi"));
}

TEST_CASE("to_text writes a condition that parses back to the same one", "[weather][conditions][grammar]") {
  for (const char* text : {"clear", "clear:10km", "visibility:1.5km", "sigma:3dB/km", "rain:8", "rain:2.5:carbonneau",
                           "rain:25:p1814", "snow:wet:0.3", "fog:kim:200m", "fog:naboulsi-radiation:1mi",
                           "rain:8:mie:lwc=0.5", "fog:advection:m=1.33+1e-8i:N=50", "fog:radiation:water=segelstein",
                           "fog:file=/tmp/a:b.csv:water=hale-querry"}) {
    INFO(text);
    const std::string once = to_text(parse_condition(text));
    CHECK(to_text(parse_condition(once)) == once);
  }
  // Built in code, written as the grammar spells it.
  CHECK(to_text(RainPowerLaw{8.0, RainLaw::seed}) == "rain:8:seed");
  CHECK(to_text(MieCondition{FogPreset::advection, ConstantIndex{{1.33, 0.0}}, AsGiven{}, std::nullopt}) == "fog:advection:m=1.33+0i");
  CHECK(to_text(Snow{SnowType::dry, 0.1}) == "snow:dry:0.1");
}

TEST_CASE("sweeps set the swept number in the typed value", "[weather][conditions][grammar]") {
  // The labels echo the text as written; the values are A + i STEP, not a
  // re-parse of the label (0.1 + 2 x 0.1 = 0.30000000000000004 in binary);
  // the last value is B as written.
  const auto snow = expand_conditions("snow:dry:0.1..0.4/0.1");
  REQUIRE(snow.size() == 4);
  CHECK(snow[2].label == "snow:dry:0.3");
  CHECK(std::get<Snow>(snow[2].condition).rate_mm_h == 0.1 + 2 * 0.1);
  CHECK(std::get<Snow>(snow[3].condition).rate_mm_h == 0.4);
  const auto vis = expand_conditions("visibility:1..2/0.5km");
  REQUIRE(vis.size() == 3);
  CHECK(vis[1].label == "visibility:1.5km");
  CHECK(std::get<Visibility>(vis[1].condition).visibility_m == 1500);
  const auto mie = expand_conditions("rain:1..3:mie:water=segelstein");
  REQUIRE(mie.size() == 3);
  CHECK(std::get<MarshallPalmerRain>(std::get<MieCondition>(mie[1].condition).drops).rate_mm_h == 2);
  for (const char* bad : {"rain:8:1..3", "snow:1..3:4", "rain:1..3km", "rain:0..2"}) {
    INFO(bad);
    CHECK_THROWS_WITH(expand_conditions(bad), Contains("bad condition") && Contains("rain:RATE"));
  }
}

TEST_CASE("m= takes the index as n+ki, n,k or n, as `attenuvis mie --m` does", "[weather][conditions][grammar]") {
  const auto index_of = [](const std::string& text) {
    return std::get<ConstantIndex>(std::get<MieCondition>(parse_condition(text)).index).m;
  };
  CHECK(index_of("fog:advection:m=1.5,0.1") == std::complex<double>(1.5, 0.1));
  CHECK(index_of("fog:advection:m=1.5+0.1i") == std::complex<double>(1.5, 0.1));
  CHECK(index_of("fog:advection:m=1.5") == std::complex<double>(1.5, 0.0));
  CHECK(index_of("rain:8:mie:m=1.33,1e-8:N=50") == std::complex<double>(1.33, 1e-8));
  for (const char* bad : {"fog:advection:m=1.5,-0.1", "fog:advection:m=1.5,", "fog:advection:m=1.5,0.1,2",
                          "fog:advection:m=,0.1"}) {
    INFO(bad);
    CHECK_THROWS_WITH(parse_condition(bad), Contains("bad condition"));
  }
  // In a comma-separated list a comma before a number stays inside the condition.
  CHECK(split_condition_list("clear,fog:advection:m=1.33,0.001:N=50,rain:8,,sigma:-1") ==
        std::vector<std::string>{"clear", "fog:advection:m=1.33,0.001:N=50", "rain:8", "sigma:-1"});
}

TEST_CASE("water=ice selects the Warren & Brandt 2008 table and writes back", "[weather][conditions][grammar]") {
  const auto c = std::get<MieCondition>(parse_condition("fog:radiation:water=ice"));
  CHECK(std::get<WaterTable>(c.index) == WaterTable::ice);
  CHECK(to_text(c) == "fog:radiation:water=ice");
  CHECK_THROWS_WITH(parse_condition("fog:radiation:water=snow"), Contains("hale-querry, segelstein or ice"));
}
