// The tolerance of an aerosol mixture is the mixture's (aerosol_optics.hpp):
// each population is integrated to a tolerance by its share of sigma_ext,
// and the mixture's reported errors must meet the tolerance and cover the
// actual error.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <variant>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

AerosolOptics optics_of(const std::string& text, double wavelength_m, double tolerance) {
  Settings s;
  s.rel_tolerance = tolerance;
  OpticsRequest r;
  r.backscatter = true;
  return aerosol_optics(std::get<AerosolCondition>(parse_condition(text)), wavelength_m, s, r);
}

}  // namespace

TEST_CASE("aerosol mixture: a minor population's tolerance follows its share, the mixture's errors cover the "
          "actual error",
          "[weather][aerosol]") {
  // OPAC clean maritime components, dry, at 1064 nm: coarse sea salt (sscm)
  // holds ~3 % of sigma_ext, so it is integrated to ~10 times the tolerance.
  const std::string mixture = "aerosol:waso=1500,ssam=20,sscm=0.0032:rh=0";
  const double wavelength = 1064e-9, tolerance = 1e-6;
  const BulkOptics b = optics_of(mixture, wavelength, tolerance).bulk;
  INFO(b.method);
  CHECK(b.shortfall.empty());
  CHECK_THAT(b.method, Contains("population tolerances loosened by their share of sigma_ext"));
  // Reference: the same mixture to 1e-9, the default (its populations'
  // reported errors are checked against brute-force sums in
  // test_aerosol_brute_force.cpp; g and beta_pi to 1e-6 at most,
  // bulk_optics.hpp).
  const BulkOptics ref = optics_of(mixture, wavelength, 1e-9).bulk;
  INFO(ref.shortfall);
  REQUIRE(ref.shortfall.empty());
  const auto covers = [](const char* what, double value, double error, double reference, double reference_error) {
    INFO(what << ": " << value << " +- " << error << " against " << reference << " +- " << reference_error);
    CHECK(std::abs(value - reference) <= error + reference_error);
  };
  covers("sigma_ext", b.extinction.value, b.extinction.error(), ref.extinction.value, ref.extinction.error());
  covers("sigma_sca", b.scattering.value, b.scattering.error(), ref.scattering.value, ref.scattering.error());
  covers("g", b.asymmetry, b.asymmetry_error, ref.asymmetry, ref.asymmetry_error);
  covers("beta_pi", b.backscatter.value, b.backscatter.error(), ref.backscatter.value, ref.backscatter.error());
  // The reported errors meet the mixture's tolerance (bulk_optics.hpp's
  // definitions: sigma relative to sigma_ext, g absolute, beta_pi relative).
  CHECK(b.extinction.error() <= tolerance * b.extinction.value);
  CHECK(b.scattering.error() <= tolerance * b.extinction.value);
  CHECK(b.asymmetry_error <= tolerance);
  CHECK(b.backscatter.error() <= tolerance * b.backscatter.value);
  // And the loosened population costs less than each population to the
  // mixture's tolerance: the sum of the three computed alone.
  std::size_t alone = 0;
  for (const char* one : {"aerosol:waso=1500:rh=0", "aerosol:ssam=20:rh=0", "aerosol:sscm=0.0032:rh=0"})
    alone += optics_of(one, wavelength, tolerance).bulk.evaluations;
  CHECK(b.evaluations < alone);
}
