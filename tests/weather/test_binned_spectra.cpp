// Binned drop spectra (a constant density per bin) by the segmented contour,
// against brute-force sums, and the refusal of tables no rule can afford.
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;

namespace {

SizeDistribution bins(const std::string& csv) {
  std::istringstream in(csv);
  return read_distribution_csv(in, "bins");
}

void check_against(const SizeDistribution& d, double wavelength, double reference) {
  const auto m = refractive_index_table("water").at(wavelength);
  const auto r = segmented_contour_extinction(d, wavelength, m);
  REQUIRE(r);
  const double sigma = r->extinction.value, error = r->extinction.error();
  INFO(std::setprecision(15) << "sigma " << sigma << " +- " << error << " (" << r->evaluations
                             << " evaluations), brute force " << reference);
  CHECK(std::abs(sigma - reference) <= error);
  CHECK(error <= 1e-9 * sigma);
}

}  // namespace

TEST_CASE("fog-drop bins at 1.55 um agree with a brute-force sum", "[weather][bins]") {
  // validation/bench/bulk_brute_force file:fogbins.csv 1550 1.3179510482199148 9.5807593159797416e-05
  // 0.004 -1 (this file; composite Gauss-Legendre inside each bin): h = 0.004 and 0.002 agree to 2e-16.
  check_against(bins("radius_lo_um,radius_hi_um,count_per_cm3\n1,3,50\n3,6,30\n6,12,10\n12,20,1\n"), 1.55e-6,
                0.013766585995872);
}

TEST_CASE("raindrop bins at 10.6 um agree with a brute-force sum", "[weather][bins]") {
  // bulk_brute_force file:rainbins.csv 10600 1.1784797999870429 0.071528861003100658 0.05 -1 (this
  // file, x up to 1185): h = 0.05 and 0.025 agree to 1e-17.
  check_against(bins("radius_lo_mm,radius_hi_mm,count_per_m3\n0.1,0.5,1000\n0.5,1,100\n1,2,10\n"), 10.6e-6,
                0.00118640238651898);
}

TEST_CASE("raindrop bins at 550 nm: within the tolerance and the evaluation budget", "[weather][bins][slow]") {
  // One bin of 0.5-1 mm drops (x from 5712 to 11424), which the real axis integrated in 260,059
  // evaluations; the segmented contour must meet 1e-9 with at most 20,000.  No brute-force sum
  // resolves resonances up to x ~ 1e4 in reasonable time; the reference is the real-axis
  // Gauss-Kronrod integral (bulk_optics.hpp, 35 s), 3.6737e-4 1/m to the five digits it was
  // recorded with, so half a unit of the last one is granted.
  const auto d = bins("radius_lo_mm,radius_hi_mm,count_per_m3\n0.5,1,100\n");
  const auto m = refractive_index_table("water").at(550e-9);
  const auto r = segmented_contour_extinction(d, 550e-9, m);
  REQUIRE(r);
  INFO(std::setprecision(12) << r->extinction.value << " +- " << r->extinction.error() << ", " << r->evaluations
                             << " evaluations");
  CHECK(r->extinction.error() <= 1e-9 * r->extinction.value);
  CHECK(r->evaluations <= 20000);
  CHECK(std::abs(r->extinction.value - 3.6737e-4) <= 0.5e-8 + r->extinction.error());
}

TEST_CASE("a table too long for any rule is refused up front with the estimate", "[weather][bins]") {
  // 100,000 rows: ~100 evaluations each on the segmented contour, one 31-point panel each on the real
  // axis; both beyond their budgets, so both refuse before evaluating anything.
  std::ostringstream csv;
  csv << "radius_um,dNdr_per_cm3_per_um\n";
  for (int i = 0; i < 100000; ++i) csv << 1 + 19.0 * i / 99999 << ",1\n";
  const SizeDistribution d = bins(csv.str());
  const auto m = refractive_index_table("water").at(550e-9);
  const auto cost = segmented_contour_cost(d, 550e-9);
  CHECK(cost.evaluations > 1e7);
  try {
    segmented_contour_extinction(d, 550e-9, m);
    FAIL("no refusal");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("estimated to take") != std::string::npos);
  }
  CHECK_THROWS_WITH(integrate_bulk_optics(d, 550e-9, mie_efficiency_batch(m), QuadratureSettings{}, m),
                    Catch::Contains("merge rows or bins"));
}
