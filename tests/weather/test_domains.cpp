// The numeric domains (domains.hpp) and hostile input: every value outside a
// domain is a clear error naming the value and the range, every loop that
// refines ends, every reader refuses what is no regular file, and no output
// carries inf or NaN.
#include <catch2/catch.hpp>

#include "../cli_run.hpp"

#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

using cli_run::Result;
using cli_run::run;

std::string temp_path(const std::string& name) { return "/tmp/attenuvis_test_domains_" + name; }
void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A failed run: non-zero status, one "attenuvis: error:" line first, naming `what`.
void check_error(const Result& r, const std::string& what) {
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, StartsWith("attenuvis: error: ") && Contains(what));
}

}  // namespace

TEST_CASE("domains: messages name the value and the range", "[weather][domains]") {
  CHECK(range_text(domain::rain_rate) == "[0.01, 500] mm/h");
  CHECK(range_text(domain::sigma) == "0 or [1e-12, 1000] 1/m");
  CHECK(read_in(domain::rain_rate, "8") == 8);
  CHECK(read_in(domain::sigma, "0") == 0);
  CHECK_THROWS_WITH(read_in(domain::rain_rate, "1000"), Contains("'1000'") && Contains("[0.01, 500] mm/h"));
  // Beyond a double: out of range, not "not a number".
  CHECK_THROWS_WITH(read_in(domain::rain_rate, "1e400"), Contains("outside its valid range"));
  CHECK_THROWS_WITH(read_in(domain::rain_rate, "1e-400"), Contains("outside its valid range"));
  CHECK_THROWS_WITH(read_in(domain::rain_rate, "abc"), Contains("not a number"));
  // A 300-digit number is quoted shortened.
  const std::string long_number(300, '9');
  try {
    read_in(domain::rain_rate, long_number);
    FAIL("accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).size() < 200);
    CHECK_THAT(e.what(), Contains("300 characters"));
  }
}

TEST_CASE("domains: conditions outside their ranges are refused with the range", "[weather][domains]") {
  // sigma = inf and V = inf were printed for these (snow rate, visibility overflow).
  CHECK_THROWS_WITH(parse_condition("snow:dry:1e308"), Contains("snow rate") && Contains("[0.01, 100] mm/h"));
  CHECK_THROWS_WITH(parse_condition("fog:kruse:1e308km"), Contains("visibility") && Contains("[1, 1e+06] m"));
  CHECK_THROWS_WITH(parse_condition("rain:1e308"), Contains("rain rate") && Contains("[0.01, 500] mm/h"));
  CHECK_THROWS_WITH(parse_condition("sigma:1e-320"), Contains("0 or [1e-12, 1000] 1/m"));
  CHECK_THROWS_WITH(parse_condition("fog:advection:N=1e300"), Contains("number density") && Contains("cm^-3"));
  CHECK_THROWS_WITH(parse_condition("fog:advection:lwc=1e300"), Contains("water content") && Contains("g/m^3"));
  CHECK_THROWS_WITH(parse_condition("fog:advection:m=1e300+0i"), Contains("real part n"));
  CHECK_THROWS_WITH(expand_conditions("rain:1..1000/100"), Contains("rain rate") && Contains("500"));
  CHECK_THROWS_WITH(parse_wavelength("1e300m"), Contains("wavelength") && Contains("[0.2, 200] um"));
  CHECK_THROWS_WITH(parse_wavelength("100nm"), Contains("[0.2, 200] um"));
  // The bounds themselves are inside.
  CHECK(parse_wavelength("200nm") == Approx(200e-9));
  CHECK(parse_wavelength("200um") == Approx(200e-6));
  CHECK_NOTHROW(parse_condition("rain:500"));
  CHECK_NOTHROW(parse_condition("visibility:1000km"));
  CHECK_NOTHROW(parse_condition("sigma:0"));
  // The grammar's help states the ranges.
  CHECK_THAT(condition_grammar(), Contains(range_text(domain::rain_rate)) && Contains(range_text(domain::sigma)));
}

TEST_CASE("domains: the user guide states every range", "[weather][domains]") {
  const std::string guide = read_text(std::string(ATTENUVIS_TEST_DATA_DIR) + "/../../docs/guide/conditions.md");
  REQUIRE(!guide.empty());
  for (const Domain* d : all_domains()) {
    INFO(d->quantity);
    CHECK_THAT(guide, Contains(range_text(*d)));
  }
}

TEST_CASE("hostile input: overflowing densities end the contour and real-axis integrals with an error",
          "[weather][domains]") {
  // The contour's refinement looped forever once the sums were inf/NaN (no
  // panel above its share of an infinite target): fog:advection:N=1e300
  // scales the density by ~5e298, which overflows its coefficient.  The
  // integrals must stop within seconds.
  const SizeDistribution huge = preset_distribution("advection").scaled(1e300);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(contour_extinction(huge, 550e-9, {1.33, 1e-8}), Contains("not finite"));
  CHECK_THROWS_AS(bulk_optics(huge, 10e-6, {1.2, 0.05}), std::runtime_error);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 60);
}

TEST_CASE("hostile input: size-distribution files", "[weather][domains][file]") {
  // /dev/zero was read forever.
  CHECK_THROWS_WITH(read_distribution_csv("/dev/zero"), Contains("not a regular file"));
  // Radii of 1e-300 um gave an effective radius of NaN and "checks passed".
  std::istringstream tiny("radius_um,dNdr_per_cm3_per_um\n1e-300,1\n2e-300,1\n");
  CHECK_THROWS_WITH(read_distribution_csv(tiny, "mem"), Contains("mem:2:") && Contains("radius") &&
                                                            Contains(range_text(domain::drop_radius)));
  // A number below the smallest normal double is out of range, not "not a finite number".
  std::istringstream subnormal("radius_um,dNdr_per_cm3_per_um\n1,1e-308\n2,1\n");
  CHECK_THROWS_WITH(read_distribution_csv(subnormal, "mem"), Contains("mem:2:") && Contains("column 2") &&
                                                                 Contains(range_text(domain::density_per_radius)));
  std::istringstream huge("radius_lo_um,radius_hi_um,count_per_cm3\n1,2,1e300\n");
  CHECK_THROWS_WITH(read_distribution_csv(huge, "mem"), Contains("mem:2:") && Contains("column 3"));
  // A UTF-8 byte-order mark before the header is no part of it.
  std::istringstream bom("\xEF\xBB\xBFradius_um,dNdr_per_cm3_per_um\n1,1\n2,1\n");
  CHECK(read_distribution_csv(bom, "mem").moment(0) == Approx(1e12 * 1e-6));
  // An absurd line length is refused with its line number.
  std::istringstream long_line("radius_um,dNdr_per_cm3_per_um\n1," + std::string(10000, '1') + "\n");
  CHECK_THROWS_WITH(read_distribution_csv(long_line, "mem"), Contains("mem:2:") && Contains("characters"));
}

TEST_CASE("hostile input: the command line", "[weather][domains][cli]") {
  check_error(run("sigma snow:dry:1e308"), "[0.01, 100] mm/h");
  check_error(run("sigma fog:kruse:1e308km"), "visibility");
  check_error(run("sigma clear --wavelength 1e300m"), "--wavelength");
  check_error(run("sigma fog:advection:N=1e300"), "number density");
  check_error(run("sigma fog:file=/dev/zero"), "not a regular file");
  check_error(run("sigma rain:8 --tolerance 0"), "--tolerance");
  check_error(run("sigma rain:8 --tolerance 0"), range_text(domain::tolerance));
  check_error(run("sigma rain:8 --threshold 1"), range_text(domain::contrast_threshold));
  check_error(run("distribution advection --bulk-density -1"), range_text(domain::bulk_density));
  check_error(run("distribution marshall-palmer:1e308"), "rain rate");
  // CLI11's own failures speak the same way, and a 300-digit value is cut.
  check_error(run("sigma"), "conditions");
  check_error(run("sigma rain:8 --no-such-option"), "--no-such-option");
  const Result r = run("table --conditions rain:8 --out " + temp_path("t.csv") + " --threads " + std::string(300, '9'));
  check_error(r, "--threads");
  CHECK(r.output.size() < 300);
}

TEST_CASE("hostile input: no inf or NaN in outputs, sigma = 0 has an unbounded visibility", "[weather][domains][cli]") {
  const std::string json = temp_path("zero.json"), csv = temp_path("zero.csv");
  std::remove(json.c_str());
  std::remove(csv.c_str());
  REQUIRE(run("table --conditions sigma:0,rain:8 --format json --out " + json).status == 0);
  const auto doc = nlohmann::json::parse(read_text(json));  // throws on inf
  CHECK(doc["rows"].size() == 2);
  CHECK(doc["rows"][0]["koschmieder_visibility_m"].is_null());  // unbounded: missing
  REQUIRE(run("table --conditions sigma:0 --out " + csv).status == 0);
  const std::string text = read_text(csv);
  CHECK_THAT(text, !Contains("inf") && !Contains("nan"));
  const Result text_out = run("sigma sigma:0");
  CHECK(text_out.status == 0);
  CHECK_THAT(text_out.output, Contains("visibility unbounded") && !Contains("inf"));
  const Result json_out = run("sigma sigma:0 --json");
  CHECK(nlohmann::json::parse(json_out.output)[0]["visibility_m"].is_null());
}

TEST_CASE("hostile input: an output over an input is refused before any work", "[weather][domains][cli]") {
  const std::string file = temp_path("drops.csv");
  const std::string content = "radius_lo_um,radius_hi_um,count_per_cm3\n5,6,100\n";
  write_text(file, content);
  check_error(run("table --conditions fog:file=" + file + " --out " + file), "input");
  CHECK(read_text(file) == content);
  // vg: an output over the eye-point file, or two outputs on one file.
  const std::string nodes = temp_path("nodes.csv");
  write_text(nodes, "1,1,1.7\n2,2,1.7\n");
  check_error(run("vg layout:0 --conditions clear --nodes " + nodes + " --out " + nodes), "--nodes");
  CHECK(read_text(nodes) == "1,1,1.7\n2,2,1.7\n");
  const std::string out = temp_path("vg.csv");
  check_error(run("vg layout:0 --conditions clear --out " + out + " --summary " + out), "both name");
}

TEST_CASE("property: random valid power-law and visibility conditions give finite sigma", "[weather][domains]") {
  std::mt19937_64 rng(20240611);
  const auto log_uniform = [&](const Domain& d) {
    const double lo = d.lo > 0 ? d.lo : 1e-12;
    std::uniform_real_distribution<double> u(std::log(lo), std::log(d.hi));
    return std::exp(u(rng));
  };
  Settings s;
  for (int i = 0; i < 2000; ++i) {
    const double wavelength = log_uniform(domain::wavelength) * domain::wavelength.unit_si;
    s.contrast_threshold = log_uniform(domain::contrast_threshold);
    s.convention = i % 2 ? Convention::itu : Convention::seed;
    const double v = log_uniform(domain::visibility);
    const Condition conditions[] = {
        RainPowerLaw{log_uniform(domain::rain_rate), RainLaw(i % 3)},
        Snow{i % 2 ? SnowType::wet : SnowType::dry, log_uniform(domain::snow_rate)},
        FogFromVisibility{VisibilityFogModel(i % 4), v},
        Visibility{v},
        ClearAir{v},
        GivenSigma{log_uniform(domain::sigma)},
    };
    for (const Condition& c : conditions) {
      const Sigma r = sigma(c, wavelength, s);
      INFO(to_text(c) << " at " << wavelength);
      REQUIRE(std::isfinite(r.per_m));
      REQUIRE(r.per_m > 0);
      REQUIRE(std::isfinite(koschmieder_visibility_m(r.per_m, s.contrast_threshold)));
    }
  }
}

TEST_CASE("property: bulk optics over random valid Mie conditions are finite, 0 <= albedo <= 1, |g| <= 1",
          "[weather][domains][mie]") {
  std::mt19937_64 rng(7);
  const auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  Settings s;
  s.rel_tolerance = 1e-4;
  for (int i = 0; i < 12; ++i) {
    const double wavelength = log_uniform(domain::wavelength.lo, domain::wavelength.hi) * 1e-6;
    MieCondition c{FogPreset(i % 2), ConstantIndex{{log_uniform(1.01, 2.0), log_uniform(1e-8, 1.0)}}, AsGiven{}};
    if (i % 3 == 1) c.rescaling = NumberDensity{log_uniform(domain::number_density.lo, domain::number_density.hi)};
    if (i % 3 == 2) c.rescaling = LiquidWaterContent{log_uniform(domain::water_content.lo, domain::water_content.hi)};
    INFO(to_text(c) << " at " << wavelength);
    const BulkOptics b = condition_bulk_optics(c, wavelength, s);
    REQUIRE(std::isfinite(b.extinction.value));
    REQUIRE(b.extinction.value > 0);
    REQUIRE(std::isfinite(b.extinction.error()));
    REQUIRE(b.albedo >= 0);
    REQUIRE(b.albedo <= 1);
    REQUIRE(std::abs(b.asymmetry) <= 1);
    const Sigma sg = sigma(c, wavelength, s);
    REQUIRE(std::isfinite(sg.per_m));
  }
}
