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

TEST_CASE("a table too long for its time limit is refused up front with the estimate", "[weather][bins]") {
  // 100,000 rows with a change of slope at each: a windowed leg of ~8 evaluations each on the
  // segmented contour (~0.8 s of one core, which it would run under its default limit of 5 s:
  // here the limit is 0.5 s), one 31-point panel each on the real axis (beyond its budget); both
  // refuse before evaluating anything.
  std::ostringstream csv;
  csv << "radius_um,dNdr_per_cm3_per_um\n";
  for (int i = 0; i < 100000; ++i) csv << 1 + 19.0 * i / 99999 << "," << 1 + 0.1 * (i % 2) << "\n";
  const SizeDistribution d = bins(csv.str());
  const auto m = refractive_index_table("water").at(550e-9);
  SegmentedContourSettings s;
  s.max_seconds = 0.5;
  const auto cost = segmented_contour_cost(d, 550e-9, s);
  CHECK(cost.evaluations > 7.5e5);
  CHECK(cost.seconds > s.max_seconds);
  try {
    segmented_contour_extinction(d, 550e-9, m, s);
    FAIL("no refusal");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("estimated to take") && Catch::Contains("merge rows or bins"));
  }
  CHECK_THROWS_WITH(integrate_bulk_optics(d, 550e-9, mie_efficiency_batch(m), QuadratureSettings{}, m),
                    Catch::Contains("merge rows or bins"));
}

TEST_CASE("a table of 10,000 rows runs, and equals the sum of its two halves", "[weather][bins]") {
  // A fog spectrum (log-normal, r_g = 5 um, sigma_g = e^0.4) sampled at 10,000 radii from 0.5 to
  // 30 um: a piecewise-linear density with a kink at every row, whose legs the budget of 400,000
  // evaluations once refused.  Reference: sigma_ext is linear in the density, so the table equals
  // the sum of its first 5,000 rows and its last 5,001 (a table each, zero outside: a jump at the
  // split, where the whole table has a kink), computed on different legs and panels.  Its path is
  // product-integrated in spans across the rows, and the legs of its dense rows are joined in
  // windows above the axis: fewer evaluations than one panel per row and a leg each up to the
  // path (spans off, the axis panels in y), which is the second reference.
  const auto table = [](int from, int to) {
    std::ostringstream csv;
    csv << std::setprecision(17) << "radius_um,dNdr_per_cm3_per_um\n";
    for (int i = from; i < to; ++i) {
      const double r = 0.5 * std::exp(std::log(60.0) * i / 9999), z = std::log(r / 5) / 0.4;
      csv << r << "," << 100 * std::exp(-0.5 * z * z) / r << "\n";
    }
    return bins(csv.str());
  };
  const auto m = refractive_index_table("water").at(550e-9);
  const auto whole = segmented_contour_extinction(table(0, 10000), 550e-9, m);
  const auto low = segmented_contour_extinction(table(0, 5000), 550e-9, m);
  const auto high = segmented_contour_extinction(table(4999, 10000), 550e-9, m);
  REQUIRE(whole);
  REQUIRE(low);
  REQUIRE(high);
  const double sum = low->extinction.value + high->extinction.value;
  INFO(std::setprecision(15) << "whole " << whole->extinction.value << " +- " << whole->extinction.error() << " ("
                             << whole->evaluations << " evaluations), halves " << sum);
  SegmentedContourSettings rows;
  rows.spans = false;
  rows.sqrt_axis_panels = false;
  const auto per_row = segmented_contour_extinction(table(0, 10000), 550e-9, m, rows);
  REQUIRE(per_row);
  CHECK(whole->method.find("windows") != std::string::npos);
  CHECK(2 * whole->evaluations < per_row->evaluations);
  CHECK(std::abs(whole->extinction.value - per_row->extinction.value) <=
        whole->extinction.error() + per_row->extinction.error());
  CHECK(whole->extinction.error() <= 1e-9 * whole->extinction.value);
  CHECK(std::abs(whole->extinction.value - sum) <=
        whole->extinction.error() + low->extinction.error() + high->extinction.error());
}
