// Parametric size distributions in the condition grammar (drops:FAMILY:...).
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>
#include <string>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

TEST_CASE("every parametric family parses and round-trips through to_text", "[weather][conditions][parametric]") {
  for (const char* text :
       {"drops:lognormal:r=5um:sg=1.5:N=100", "drops:lognormal:sg=1.2:r=0.3um:lwc=0.2:water=ice",
        "drops:gamma:r=4um:alpha=6:N=50:m=1.5+0.01i", "drops:mgamma:a=0.027:alpha=3:b=0.3",
        "drops:mgamma:a=607.5:alpha=6:b=3:gamma=1", "drops:mgamma:rc=4um:alpha=6:gamma=1:N=100",
        "drops:exponential:n0=8000:lambda=2.5", "drops:powerlaw:nu=4:rmin=0.1um:rmax=10um:N=1000"}) {
    INFO(text);
    const Condition c = parse_condition(text);
    REQUIRE(std::holds_alternative<MieCondition>(c));
    REQUIRE(std::holds_alternative<ParametricDrops>(std::get<MieCondition>(c).drops));
    const std::string once = to_text(c);
    INFO(once);
    CHECK(to_text(parse_condition(once)) == once);
    // The distribution it stands for is the same after the round trip (exact numbers).
    const auto d1 = condition_distribution(std::get<MieCondition>(c));
    const auto d2 = condition_distribution(std::get<MieCondition>(parse_condition(once)));
    CHECK(d1.moment(2) == d2.moment(2));
  }
}

TEST_CASE("parametric drops: the user's numbers arrive as given", "[weather][conditions][parametric]") {
  // Deirmendjian's r_c form: b = alpha / (gamma rc^gamma) (Deirmendjian 1969, eq. for the mode radius).
  const auto c = std::get<MieCondition>(parse_condition("drops:mgamma:rc=4um:alpha=6:N=100"));
  const auto& g = std::get<ModifiedGammaDrops>(std::get<ParametricDrops>(c.drops).family);
  CHECK(g.b == Approx(1.5).epsilon(1e-15));
  // The advection preset written out by hand is the preset (P.1817-1 / seed: alpha 3, a 0.027, b 0.3).
  const auto by_hand = condition_distribution(std::get<MieCondition>(parse_condition("drops:mgamma:a=0.027:alpha=3:b=0.3")));
  CHECK(by_hand.moment(2) == Approx(preset_distribution("advection").moment(2)).epsilon(1e-14));
  // A log-normal with N= holds that many drops per cm^3 and its median radius.
  const auto ln = condition_distribution(std::get<MieCondition>(parse_condition("drops:lognormal:r=5um:sg=1.5:N=100")));
  CHECK(ln.moment(0) == Approx(100e6).epsilon(1e-12));
  CHECK(ln.moment(1) / ln.moment(0) == Approx(5e-6 * std::exp(0.5 * std::pow(std::log(1.5), 2))).epsilon(1e-12));
}

TEST_CASE("parametric drops: errors name the parameter and its field", "[weather][conditions][parametric]") {
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5um:sg=0.9:N=100"),
                    Contains("parameter sg= (field 4)") && Contains("in (1, 20]"));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5:sg=1.5:N=100"),
                    Contains("parameter r= (field 3)") && Contains("unit"));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5um:N=100"), Contains("needs the parameter sg="));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5um:sg=1.5"), Contains("needs its amount"));
  CHECK_THROWS_WITH(parse_condition("drops:gamma:r=4um:alpha=x:N=1"), Contains("parameter alpha= (field 4)"));
  CHECK_THROWS_WITH(parse_condition("drops:mgamma:a=1:alpha=3:b=-1"), Contains("parameter b= (field 5)"));
  CHECK_THROWS_WITH(parse_condition("drops:mgamma:rc=4um:a=1:alpha=3:N=1"), Contains("not both"));
  CHECK_THROWS_WITH(parse_condition("drops:powerlaw:nu=4:rmin=10um:rmax=1um:N=1"), Contains("rmin < rmax"));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5um:r=6um:sg=1.5:N=1"), Contains("given twice (fields 3 and 4)"));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=5um:sg=1.5:N=100:q=1"), Contains("unexpected field 'q=1'"));
  CHECK_THROWS_WITH(parse_condition("drops:weibull:r=5um"), Contains("unknown drops 'weibull'"));
  CHECK_THROWS_WITH(parse_condition("drops:lognormal:r=1km:sg=1.5:N=1"), Contains("parameter r=") && Contains("radius"));
}

TEST_CASE("parametric drops: sigma (contour rule) agrees with the bulk quadrature within its error",
          "[weather][conditions][parametric][slow]") {
  // An absorbing index (k = 1e-3: no resonance floor) keeps the real-axis quadrature fast; one
  // water case (Hale & Querry 1973) with small drops covers the resonance path.
  for (const char* text :
       {"drops:lognormal:r=2um:sg=1.5:N=100:m=1.33+0.001i", "drops:gamma:r=3um:alpha=4:N=100:m=1.33+0.001i",
        "drops:mgamma:rc=2um:alpha=6:gamma=0.5:N=100:m=1.33+0.001i", "drops:exponential:n0=8000:lambda=20:m=1.33+0.001i",
        "drops:powerlaw:nu=4:rmin=0.1um:rmax=5um:N=1000:m=1.5+0.01i", "drops:lognormal:r=1um:sg=1.4:N=100"}) {
    INFO(text);
    const auto c = std::get<MieCondition>(parse_condition(text));
    const Sigma s = sigma(c, 550e-9, {});
    const BulkOptics b = condition_bulk_optics(c, 550e-9, {});
    INFO(std::setprecision(12) << "sigma " << s.per_m << " +- " << s.error_per_m << "; quadrature "
                               << b.extinction.value << " +- " << b.extinction.error() << "; " << s.note);
    CHECK(s.per_m > 0);
    CHECK(std::abs(s.per_m - b.extinction.value) <= s.error_per_m + b.extinction.error());
    CHECK(s.error_per_m < 1e-6 * s.per_m);
  }
}

TEST_CASE("parametric drops: radii with units are the nearest doubles", "[weather][conditions][parametric]") {
  const auto c = std::get<MieCondition>(parse_condition("drops:lognormal:r=5um:sg=1.5:N=100"));
  CHECK(std::get<LogNormalDrops>(std::get<ParametricDrops>(c.drops).family).median_radius_m == 5e-6);
  CHECK(to_text(c) == "drops:lognormal:r=5e-06m:sg=1.5:N=100");
}
