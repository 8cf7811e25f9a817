// End-to-end tests of `attenuvis optics`.
#include <catch2/catch.hpp>

#include "../cli_run.hpp"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "attenuvis/weather.hpp"

using Catch::Matchers::Contains;
using cli_run::run;

TEST_CASE("optics prints every bulk quantity with its error and units as JSON", "[weather][cli][optics]") {
  // Radiation fog at 1.55 um: a fraction of a second.
  const auto r = run("optics fog:radiation --wavelength 1.55um --moments 4 --angles 0:180:90 --json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.output);
  REQUIRE(j.size() == 1);
  const auto& o = j[0];
  CHECK(o["condition"] == "fog:radiation");
  for (const char* key : {"sigma_ext", "sigma_sca", "sigma_abs", "backscatter"}) {
    INFO(key);
    CHECK(o[key]["value"].get<double>() > 0);
    CHECK(o[key]["error"].get<double>() > 0);
    CHECK(o[key]["error"].get<double>() < 1e-2 * o[key]["value"].get<double>());
  }
  CHECK(o["sigma_ext"]["units"] == "1/m");
  CHECK(o["backscatter"]["units"] == "1/(m sr)");
  CHECK(o["lidar_ratio"]["units"] == "sr");
  // The lidar ratio is sigma_ext / beta_pi, and the moments start at chi_0 = 1, chi_1 = g.
  CHECK(o["lidar_ratio"]["value"].get<double>() ==
        Approx(o["sigma_ext"]["value"].get<double>() / o["backscatter"]["value"].get<double>()).epsilon(1e-12));
  REQUIRE(o["moments"]["values"].size() == 5);
  CHECK(o["moments"]["values"][0].get<double>() == Approx(1.0).epsilon(1e-12));
  // chi_1 and g come from separate passes (moments cost O(x^2) per drop): equal within their errors.
  CHECK(std::abs(o["moments"]["values"][1].get<double>() - o["g"]["value"].get<double>()) <=
        o["moments"]["errors"][1].get<double>() + o["g"]["error"].get<double>());
  REQUIRE(o["phase_function"]["angles_deg"].size() == 3);
  CHECK(o["phase_function"]["angles_deg"][2].get<double>() == 180.0);
  // Same numbers as the library (one code path, condition_optics).
  auto c = std::get<attenuvis::weather::MieCondition>(attenuvis::weather::parse_condition("fog:radiation"));
  attenuvis::weather::OpticsRequest req;
  req.legendre_moments = 4;
  req.angles_deg = {0, 90, 180};
  const auto lib = attenuvis::weather::condition_optics(c, 1.55e-6, {}, req);
  CHECK(o["backscatter"]["value"].get<double>() == lib.bulk.backscatter.value);
  CHECK(o["phase_function"]["values"][1].get<double>() == lib.bulk.phase[1]);
}

TEST_CASE("optics text names every quantity and the method", "[weather][cli][optics]") {
  const auto r = run("optics fog:radiation --wavelength 1.55um --moments 2");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("sigma_ext") && Contains("lidar ratio") && Contains("1/(m sr)") &&
                           Contains("Legendre moments") && Contains("method: adaptive Gauss-Kronrod"));
}

TEST_CASE("optics rejects bad input with a message naming it", "[weather][cli][optics]") {
  auto r = run("optics rain:8 --wavelength 1.55um");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("condition 1") && Contains("has no particles"));
  r = run("optics fog:radiation --angles 0:200:10");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("--angles '0:200:10'") && Contains("[0, 180]"));
  r = run("optics fog:radiation --angles 0:x:10");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("--angles") && Contains("'x'"));
  r = run("optics fog:radiation --polarised");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("--polarised needs --moments"));
  r = run("optics fog:radiation --moments -3");
  CHECK(r.status != 0);
  r = run("optics fog:nonesuch");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("nonesuch"));
}

TEST_CASE("optics takes parametric drops with the user's numbers", "[weather][cli][optics][parametric]") {
  const auto r = run("optics drops:lognormal:r=2um:sg=1.5:N=100 drops:gamma:r=3um:alpha=6:lwc=0.1:water=ice "
                     "--wavelength 1.55um --angles 0,180 --json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.output);
  REQUIRE(j.size() == 2);
  CHECK(j[0]["condition"] == "drops:lognormal:r=2um:sg=1.5:N=100");
  CHECK_THAT(j[1]["refractive_index"].get<std::string>(), Contains("ice"));
  for (const auto& o : j) {
    CHECK(o["sigma_ext"]["value"].get<double>() > 0);
    CHECK(o["phase_function"]["values"][0].get<double>() > o["phase_function"]["values"][1].get<double>());
  }
}
