// Core–shell particles over a size distribution (attenuvis/weather/coated_optics.hpp)
// and their condition grammar (:coat=F:shell=N+Ki).  References: the
// homogeneous bulk optics of the same particles where a coating is no coating
// (no shell, or a shell of the core's index: then the particles are
// homogeneous spheres of the outer radius, a log-normal of median r (1 − f)^(−1/3)),
// and the layered sphere itself at a single radius.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <string>

#include "attenuvis/mie/layered.hpp"
#include "attenuvis/weather.hpp"
#include "attenuvis/weather/coated_optics.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

// Two integrals of the same quantity, each with its reported error: they
// agree within the sum of the two.
void check_within_errors(const IntegralEstimate& a, const IntegralEstimate& b, const char* what) {
  INFO(what << ": " << a.value << " +- " << a.error() << " vs " << b.value << " +- " << b.error());
  CHECK(std::abs(a.value - b.value) <= a.error() + b.error());
}

const double kLambda = 550e-9;

}  // namespace

TEST_CASE("coated bulk optics: no shell is the homogeneous core", "[weather][coated]") {
  const SizeDistribution d = SizeDistribution::log_normal(1e9, 0.1e-6, 1.8);
  const std::complex<double> soot(1.75, 0.44);
  const BulkOptics coated = coated_bulk_optics(d, kLambda, soot, Coating{0.0, soot});
  const BulkOptics plain = integrate_bulk_optics(d, kLambda, mie_efficiency_batch(soot), {}, soot);
  // The layered sphere leaves a zero-thickness shell out: the same efficiencies, the same integral.
  CHECK(coated.extinction.value == plain.extinction.value);
  CHECK(coated.asymmetry == plain.asymmetry);
}

TEST_CASE("coated bulk optics: a shell of the core's index is a larger homogeneous sphere", "[weather][coated]") {
  const double f = 0.5, s = std::cbrt(1 / (1 - f));
  for (const std::complex<double> m : {std::complex<double>(1.43, 1e-3), std::complex<double>(1.75, 0.44)}) {
    INFO("m = " << m);
    const BulkOptics coated =
        coated_bulk_optics(SizeDistribution::log_normal(1e9, 0.1e-6, 1.8), kLambda, m, Coating{f, m});
    const BulkOptics outer = integrate_bulk_optics(SizeDistribution::log_normal(1e9, 0.1e-6 * s, 1.8), kLambda,
                                                   mie_efficiency_batch(m), {}, m);
    check_within_errors(coated.extinction, outer.extinction, "extinction");
    check_within_errors(coated.scattering, outer.scattering, "scattering");
    check_within_errors(coated.absorption, outer.absorption, "absorption");
    CHECK(std::abs(coated.asymmetry - outer.asymmetry) <= coated.asymmetry_error + outer.asymmetry_error + 1e-12);
  }
}

TEST_CASE("coated efficiencies are the layered sphere's per core cross section", "[weather][coated]") {
  // The fraction through a volatile: a constant cbrt would be folded by the
  // compiler (correctly rounded), the library's is glibc's (within an ulp).
  volatile double fraction = 0.7;
  const Coating sulphate{fraction, {1.43, 1e-8}};
  const std::complex<double> soot(1.75, 0.44);
  const double x = 3.0, s = std::cbrt(1.0 / (1.0 - sulphate.shell_volume_fraction));
  Efficiency e;
  coated_efficiency_batch(soot, sulphate)(&x, 1, &e);
  const auto q = attenuvis::mie::layered_sphere({x, s * x}, {soot, sulphate.shell_m});
  CHECK(e.qext == q.qext * (s * s));
  CHECK(e.qback == q.qback * (s * s));
  CHECK(e.g == q.g);
  QuadratureSettings angular;
  angular.legendre_moments = 4;
  const Efficiency one = coated_efficiencies(soot, sulphate, angular)(x);
  CHECK(one.qext == e.qext);
  REQUIRE(one.moments.size() == 5);
  CHECK(std::abs(one.moments[1] - q.g) <= 1e-13);  // chi_1 = g
}

TEST_CASE("coated conditions: grammar, sigma with its error, and the refusals", "[weather][coated][grammar]") {
  const Condition c = parse_condition("drops:lognormal:r=0.05um:sg=1.8:N=1000:m=1.75+0.44i:coat=0.5:shell=1.43+1e-8i");
  const std::string text = to_text(c);
  CHECK_THAT(text, Contains(":coat=0.5:shell=1.43+1e-08i"));
  CHECK(to_text(parse_condition(text)) == text);
  const Sigma sg = sigma(c, kLambda, Settings{});
  CHECK(sg.per_m > 0);
  CHECK(sg.error_per_m <= 1e-8 * sg.per_m);
  CHECK_THAT(sg.model, Contains("core-shell"));
  // The coating changes sigma (a coated soot core extinguishes more than the bare one).
  const Sigma bare = sigma(parse_condition("drops:lognormal:r=0.05um:sg=1.8:N=1000:m=1.75+0.44i"), kLambda, Settings{});
  CHECK(sg.per_m > 1.1 * bare.per_m);
  CHECK_THROWS_WITH(parse_condition("fog:advection:coat=0.5"), Contains("coat= needs shell="));
  CHECK_THROWS_WITH(parse_condition("fog:advection:shell=1.5"), Contains("shell= needs coat="));
  CHECK_THROWS_WITH(parse_condition("fog:advection:coat=1:shell=1.5"), Contains("shell volume fraction"));
  CHECK_THROWS_WITH(parse_condition("fog:advection:coat=0.5:shell=1.5-0.1i"), Contains("refractive index"));
}
