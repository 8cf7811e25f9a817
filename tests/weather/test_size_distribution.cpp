// Size distributions: moments against closed forms and the seed paper's fog
// table, tails, normalisation, and the CSV reader's validation.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {
const double kPi = boost::math::constants::pi<double>();
std::string data(const std::string& name) { return std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/" + name; }
}  // namespace

TEST_CASE("fog presets reproduce the seed paper's N and W (Table 'Attenuation coefficient parameters for Fog')",
          "[weather][distribution]") {
  // Seed paper (Schwartz, Vinnikov, Federici, SimAUD 2021), Table tab:itu-fog:
  // HA: N = 20 cm^-3, W = 0.37 g/m^3, r_m = 10 um;  MR: N = 200 cm^-3, W = 0.02 g/m^3, r_m = 2 um.
  auto ha = moments(preset_distribution("advection"));
  CHECK(ha.number_per_m3 * 1e-6 == Approx(20.0).epsilon(1e-12));  // a Gamma(4)/b^4 = 0.027*6/0.3^4 = 20 exactly
  CHECK(ha.water_content_kg_m3 * 1e3 == Approx(0.37).margin(0.005));  // seed rounds to 2 digits
  CHECK(ha.mode_radius_m * 1e6 == Approx(10.0).epsilon(1e-12));
  auto mr = moments(preset_distribution("radiation"));
  CHECK(mr.number_per_m3 * 1e-6 == Approx(200.0).epsilon(1e-12));
  CHECK(mr.mode_radius_m * 1e6 == Approx(2.0).epsilon(1e-12));
  // The seed's 0.02 g/m^3 is rounded: (4/3) pi rho a Gamma(10)/b^10 = 0.015638 g/m^3 (closed form,
  // a = 607.5 cm^-3 um^-7, b = 3 um^-1, rho = 1 g/cm^3).
  double w_exact = 4.0 / 3.0 * kPi * 607.5 * 362880.0 / std::pow(3.0, 10) * 1e-6;  // um^3/cm^3 -> g/m^3
  CHECK(mr.water_content_kg_m3 * 1e3 == Approx(w_exact).epsilon(1e-12));
  CHECK(mr.water_content_kg_m3 * 1e3 == Approx(0.02).margin(0.005));
}

TEST_CASE("modified gamma moments agree with direct integration", "[weather][distribution]") {
  // Independent check: exp_sinh quadrature of r^p n(r) on (0, inf) vs the Gamma-function closed form.
  auto d = SizeDistribution::modified_gamma_um(2.0, 2.5, 0.7, 1.7);
  boost::math::quadrature::exp_sinh<double> integrator;
  for (double p : {0.0, 1.0, 2.0, 3.0}) {
    // In t = r / 1 um, so the integrand is O(1) where it matters.
    double direct = 1e-6 * std::pow(1e-6, p) *
                    integrator.integrate([&](double t) { double n = d.density(t * 1e-6); return n == 0 ? 0.0 : std::pow(t, p) * n; }, 1e-14);
    CHECK(d.moment(p) == Approx(direct).epsilon(1e-10));
  }
}

TEST_CASE("log-normal and Marshall-Palmer moments", "[weather][distribution]") {
  auto ln = SizeDistribution::log_normal(1e8, 1e-6, 3.0);
  double s = std::log(3.0);
  CHECK(ln.moment(0) == Approx(1e8).epsilon(1e-14));
  CHECK(ln.moment(3) == Approx(1e8 * 1e-18 * std::exp(4.5 * s * s)).epsilon(1e-13));
  // Marshall & Palmer (1948): N = N0 / Lambda with N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1.
  auto mp = SizeDistribution::marshall_palmer(8.0);
  CHECK(mp.moment(0) == Approx(8000.0 / (4.1 * std::pow(8.0, -0.21))).epsilon(1e-12));
}

TEST_CASE("support leaves exactly the requested tail fraction outside", "[weather][distribution]") {
  for (const auto& d : {preset_distribution("advection"), SizeDistribution::log_normal(1e8, 1e-6, 3.0),
                        SizeDistribution::modified_gamma_um(1.0, 50.0, 1.0, 40.0)}) {
    auto sup = d.support(2.0, 1e-10);
    REQUIRE(sup.breakpoints_m.size() >= 2);
    double inside = 0;
    boost::math::quadrature::exp_sinh<double> unused;
    (void)unused;
    double lo = sup.breakpoints_m.front(), hi = sup.breakpoints_m.back();
    CHECK(lo < hi);
    CHECK(sup.omitted_moment / sup.total_moment == Approx(1e-10).epsilon(0.01));
    (void)inside;
  }
}

TEST_CASE("normalisation to a number or a water content", "[weather][distribution]") {
  auto d = preset_distribution("advection");
  CHECK(moments(normalised_to_number(d, 5e7)).number_per_m3 == Approx(5e7).epsilon(1e-13));
  CHECK(moments(normalised_to_water_content(d, 1e-4)).water_content_kg_m3 == Approx(1e-4).epsilon(1e-13));
}

TEST_CASE("CSV distributions: points, dN/dlnr and a single bin", "[weather][distribution][file]") {
  auto tri = read_distribution_csv(data("points_dndr.csv"));
  CHECK(tri.moment(0) * 1e-6 == Approx(20.0).epsilon(1e-13));  // triangle area: 0.5 * 4 um * 10
  CHECK(tri.density(4e-6) * 1e-12 == Approx(10.0));
  auto one = read_distribution_csv(data("one_bin.csv"));
  CHECK(one.moment(0) * 1e-6 == Approx(100.0).epsilon(1e-13));
  // Bin with uniform dN/dr: <r^3> N = 100 (10.5^4 - 9.5^4)/(4 * 1) um^3 cm^-3.
  double m3 = 100.0 * (std::pow(10.5, 4) - std::pow(9.5, 4)) / 4.0;
  CHECK(one.moment(3) == Approx(m3 * 1e-18 * 1e6).epsilon(1e-12));
  auto ln = read_distribution_csv(data("points_dndlnr.csv"));
  CHECK(ln.density(2e-6) == Approx(8e6 / 2e-6));
}

TEST_CASE("CSV distributions: errors name the line", "[weather][distribution][file]") {
  CHECK_THROWS_WITH(read_distribution_csv(data("bad_decreasing.csv")), Contains(":4:") && Contains("increase"));
  CHECK_THROWS_WITH(read_distribution_csv(data("bad_negative.csv")), Contains(":3:") && Contains("negative"));
  CHECK_THROWS_WITH(read_distribution_csv(data("bad_header.csv")), Contains(":1:") && Contains("radius_um"));
  CHECK_THROWS_WITH(read_distribution_csv(data("bad_one_point.csv")), Contains("at least 2"));
  CHECK_THROWS_WITH(read_distribution_csv(data("bad_number.csv")), Contains(":4:") && Contains("abc"));
  CHECK_THROWS_WITH(read_distribution_csv(data("does_not_exist.csv")),
                    Contains("does_not_exist.csv") && Contains("No such file"));
  std::istringstream overlap("radius_lo_um,radius_hi_um,count_per_cm3\n1,3,1\n2,4,1\n");
  CHECK_THROWS_WITH(read_distribution_csv(overlap, "mem"), Contains("mem:3:") && Contains("overlap"));
}

TEST_CASE("presets reject unknown names with the list", "[weather][distribution]") {
  CHECK_THROWS_WITH(preset_distribution("drizzle"), Contains("advection") && Contains("radiation"));
  CHECK(preset_distribution("gunn-marshall:2").moment(0) > 0);
}

TEST_CASE("mode radius of tabulated distributions does not depend on how many particles there are",
          "[weather][distribution]") {
  // A bin has a constant density: its mode is taken at the bin's middle.  The
  // density's size must not enter: sparse large particles (here 5e-7 hail
  // stones per m^3 between 1 and 2 mm radius, n = 5e-4 m^-4, numerically below
  // the radius in metres) have the same mode as a dense bin.
  std::istringstream sparse("radius_lo_mm,radius_hi_mm,count_per_m3\n1,2,5e-7\n");
  const auto hail = read_distribution_csv(sparse, "sparse hail");
  CHECK(moments(hail).mode_radius_m == Approx(1.5e-3).epsilon(1e-12));
  std::istringstream dense("radius_lo_mm,radius_hi_mm,count_per_m3\n1,2,5e+7\n");
  CHECK(moments(read_distribution_csv(dense, "dense hail")).mode_radius_m == moments(hail).mode_radius_m);
  // Scaling n by any factor leaves the mode where it was.
  for (double f : {1e-20, 1e-3, 1e6})
    CHECK(moments(hail.scaled(f)).mode_radius_m == moments(hail).mode_radius_m);
  // A plateau between two equal points: its middle; a peak at a point: that point.
  std::istringstream plateau("radius_um,dNdr_per_cm3_per_um\n1,0\n2,5\n3,5\n4,0\n");
  CHECK(moments(read_distribution_csv(plateau, "plateau")).mode_radius_m == Approx(2.5e-6).epsilon(1e-12));
  std::istringstream peak("radius_um,dNdr_per_cm3_per_um\n1,0\n2,5\n3,1\n");
  CHECK(moments(read_distribution_csv(peak, "peak")).mode_radius_m == Approx(2e-6).epsilon(1e-12));
}
