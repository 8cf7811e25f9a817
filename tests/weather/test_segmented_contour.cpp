// sigma_ext of tables and power laws by Cauchy on each piece (weather/segmented_contour.hpp).
//
// References, each named where it is used:
//  - absorbing drops (m = 1.33 + 0.01i, no resonance floor): the real-axis
//    rule of bulk_optics.hpp over the same piecewise density, at rel. tol.
//    1e-11 (it resolves Q_ext there and reports no resonance error);
//  - nearly lossless water (Hale & Querry 1973 via refractive_index_table):
//    the real axis cannot resolve the resonances, so the reference is the
//    same route along an independent path (height 6 instead of 4, slope 0.15
//    instead of 0.25, so other legs and other path points; one Gauss-Kronrod
//    panel per row at least instead of product-integrated spans across rows,
//    the legs' panels on the axis by the 15-point rule in y instead of the
//    7-point rule in sqrt(y)), S(0) in long double, rel. tol. 1e-12, every panel verified by halving.
//    The real-axis value must lie within its own (resonance) error of it as well.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;

namespace {

const std::complex<double> kAbsorbing(1.33, 0.01);
constexpr double kPerCm3PerUm = 1e12;  // m^-4

// A table through the given (radius um, density cm^-3 um^-1) points.
SizeDistribution table_through(const std::vector<std::pair<double, double>>& points, const std::string& name) {
  std::vector<TabulatedSegment> segments;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    segments.push_back({points[i].first * 1e-6, points[i + 1].first * 1e-6, points[i].second * kPerCm3PerUm,
                        points[i + 1].second * kPerCm3PerUm});
  return SizeDistribution::tabulated(segments, name);
}

// 200 points log-spaced over the radii holding all but 1e-12 of the r^2
// moment of the log-normal r_g = 5 um, sigma_g = 1.5, 100 cm^-3 (the table of
// validation/bench/bulk_optics_speed.cpp).
SizeDistribution log_normal_table(int points = 200) {
  const auto analytic = SizeDistribution::log_normal(1e8, 5e-6, 1.5);
  const auto support = analytic.support(2.0, 1e-12);
  const double lo = std::log(support.breakpoints_m.front()), hi = std::log(support.breakpoints_m.back());
  std::vector<TabulatedSegment> segments;
  for (int i = 0; i + 1 < points; ++i) {
    const double r0 = std::exp(lo + (hi - lo) * i / (points - 1));
    const double r1 = std::exp(lo + (hi - lo) * (i + 1) / (points - 1));
    segments.push_back({r0, r1, analytic.density(r0), analytic.density(r1)});
  }
  return SizeDistribution::tabulated(segments, std::to_string(points) + "-point log-normal");
}

// The shapes a file can have that a smooth distribution has not.
std::vector<SizeDistribution> awkward_tables() {
  return {
      // A kink: a triangle, zero at both ends.
      table_through({{1, 0}, {6, 10}, {20, 0}}, "triangle (kink at 6 um)"),
      // Truncated at both ends: the density jumps from 0 to its value there.
      table_through({{2, 3}, {4, 9}, {7, 6}, {12, 1.5}}, "truncated at 2 and 12 um"),
      // A zero segment between two humps.
      table_through({{1, 0.5}, {3, 2}, {5, 0}, {8, 0}, {10, 1}, {15, 0.3}}, "zero segment 5-8 um"),
      // Bins with a gap: jumps at every edge.
      SizeDistribution::tabulated({{1e-6, 2e-6, 4e12, 4e12}, {3e-6, 5e-6, 1e12, 1e12}, {5e-6, 9e-6, 2e11, 2e11}},
                                  "bins with a gap"),
  };
}

ContourExtinction route(const SizeDistribution& d, double wavelength, std::complex<double> m,
                        const SegmentedContourSettings& s = {}) {
  const auto c = segmented_contour_extinction(d, wavelength, m, s);
  REQUIRE(c);
  return *c;
}

// The independent-path reference for nearly lossless drops (see the head of this file).
double independent_path_reference(const SizeDistribution& d, double wavelength, std::complex<double> m) {
  SegmentedContourSettings r;
  r.rel_tolerance = 1e-12;
  r.height = 6;
  r.angle = 0.15;
  r.verify = true;
  r.spans = false;
  r.sqrt_axis_panels = false;
  r.max_evaluations = 2000000;
  return route(d, wavelength, m, r).extinction.value;
}

}  // namespace

// [slow]: its real-axis check resolves water's resonances at 550 nm to 1e-9
// (22 s under ASan); the sanitizer tree runs the same table's contour in the
// test below.
TEST_CASE("segmented contour: 200-point log-normal table in water, reported error bounds the actual one",
          "[weather][segmented][slow]") {
  for (double wavelength : {550e-9, 1.55e-6}) {
    const auto table = log_normal_table();
    const auto m = refractive_index_table("water").at(wavelength);
    const auto c = route(table, wavelength, m);
    const double reference = independent_path_reference(table, wavelength, m);
    const double actual = std::abs(c.extinction.value - reference);
    // The real-axis rule over the same table: its value must lie within its
    // own error (at 550 nm mostly the unresolved-resonance term) of the reference.
    const BulkOptics axis = bulk_optics(table, wavelength, m);
    const auto analytic = contour_extinction(SizeDistribution::log_normal(1e8, 5e-6, 1.5), wavelength, m);
    REQUIRE(analytic);
    INFO(std::setprecision(13) << wavelength << " m: segmented " << c.extinction.value << " +- "
                               << c.extinction.error() << " (" << c.evaluations << " evaluations), reference "
                               << reference << ", actual error " << actual << "; real axis " << axis.extinction.value
                               << " +- " << axis.extinction.error() << " (" << axis.evaluations << ")");
    CHECK(actual <= c.extinction.error());
    CHECK(c.extinction.error() <= 1.1e-9 * c.extinction.value);
    CHECK(std::abs(axis.extinction.value - reference) <= axis.extinction.error());
    CHECK(c.method.find("segmented contour") != std::string::npos);
    WARN(std::setprecision(10) << "200-point log-normal table at " << wavelength * 1e9 << " nm: segmented contour "
                               << c.extinction.value << " +- " << std::setprecision(2) << c.extinction.error()
                               << " 1/m, actual error " << actual << ", " << c.evaluations
                               << " evaluations; real axis " << axis.evaluations << "; the analytic log-normal "
                               << std::setprecision(10) << analytic->extinction.value << " by "
                               << analytic->evaluations << " (it differs by the table's interpolation)");
  }
}

TEST_CASE("segmented contour: the error bound holds at every tolerance and path height", "[weather][segmented]") {
  // Loose tolerances leave the fewest panels (one per piece and per leg):
  // the reported error must still bound the actual one, against the
  // independent-path reference (head of this file).
  const auto table = log_normal_table();
  const auto m = refractive_index_table("water").at(550e-9);
  const double reference = independent_path_reference(table, 550e-9, m);
  for (double height : {2.0, 4.0})
    for (double tol : {1e-4, 1e-6, 1e-8}) {
      SegmentedContourSettings s;
      s.height = height;
      s.rel_tolerance = tol;
      const auto c = route(table, 550e-9, m, s);
      const double actual = std::abs(c.extinction.value - reference);
      INFO(std::setprecision(13) << "h " << height << ", tol " << tol << ": " << c.extinction.value << " +- "
                                 << c.extinction.error() << " (" << c.evaluations << " evaluations), reference "
                                 << reference << ", actual error " << actual);
      CHECK(actual <= c.extinction.error());
      CHECK(c.extinction.error() <= 1.1 * tol * reference);
    }
}

TEST_CASE("segmented contour agrees with the real axis for absorbing drops", "[weather][segmented]") {
  // Reference: the real-axis rule at 1e-11 over the same density (head of this file).
  std::vector<SizeDistribution> cases = awkward_tables();
  cases.push_back(log_normal_table(40));
  cases.push_back(SizeDistribution::power_law(1e4, 3.5, 0.1e-6, 10e-6));  // Junge, n = C r^-3.5
  for (const auto& d : cases) {
    const auto c = route(d, 550e-9, kAbsorbing);
    QuadratureSettings q;
    q.rel_tolerance = 1e-11;
    const BulkOptics axis = bulk_optics(d, 550e-9, kAbsorbing, q);
    INFO(std::setprecision(13) << d.describe() << ": segmented " << c.extinction.value << " +- "
                               << c.extinction.error() << " (" << c.evaluations << " evaluations); real axis "
                               << axis.extinction.value << " +- " << axis.extinction.error());
    CHECK(axis.extinction.resonance_error == 0);
    CHECK(std::abs(c.extinction.value - axis.extinction.value) <= c.extinction.error() + axis.extinction.error());
    CHECK(c.extinction.error() <= 1.1e-9 * c.extinction.value);
  }
}

TEST_CASE("segmented contour: kinks, truncated ends, zero segments, bins and a power law in water", "[weather][segmented]") {
  // Reference: the independent path (head of this file); the real axis within its resonance error.
  const auto m = refractive_index_table("water").at(550e-9);
  std::vector<SizeDistribution> cases = awkward_tables();
  cases.push_back(SizeDistribution::power_law(1e4, 3.5, 0.1e-6, 10e-6));  // Junge, n = C r^-3.5
  for (const auto& d : cases) {
    const auto c = route(d, 550e-9, m);
    const double reference = independent_path_reference(d, 550e-9, m);
    const double actual = std::abs(c.extinction.value - reference);
    QuadratureSettings q;
    q.rel_tolerance = 1e-7;
    const BulkOptics axis = bulk_optics(d, 550e-9, m, q);
    INFO(std::setprecision(13) << d.describe() << ": segmented " << c.extinction.value << " +- "
                               << c.extinction.error() << " (" << c.evaluations << " evaluations), reference "
                               << reference << ", actual error " << actual << "; real axis " << axis.extinction.value
                               << " +- " << axis.extinction.error());
    CHECK(actual <= c.extinction.error());
    CHECK(c.extinction.error() <= 1.1e-9 * c.extinction.value);
    CHECK(std::abs(axis.extinction.value - reference) <= axis.extinction.error());
  }
}

TEST_CASE("sigma() of a distribution file takes the segmented contour and says so", "[weather][segmented]") {
  const std::string path = "segmented_contour_test_table.csv";
  {
    std::ofstream out(path);
    out << "radius_um,dNdr_per_cm3_per_um\n1,0\n3,8\n6,5\n10,1\n15,0\n";
  }
  const Sigma s = sigma(parse_condition("fog:file=" + path), 550e-9, Settings{});
  std::remove(path.c_str());
  INFO(s.note);
  CHECK(s.note.find("segmented contour") != std::string::npos);
  CHECK(s.error_per_m <= 1.1e-9 * s.per_m);
  double sum = 0;
  for (const auto& term : s.error_terms) sum += term.per_m;
  CHECK(sum == Approx(s.error_per_m).epsilon(1e-12));
}

TEST_CASE("segmented contour declines what is not a table or reaches too far", "[weather][segmented]") {
  CHECK_FALSE(segmented_contour_extinction(preset_distribution("advection"), 550e-9, kAbsorbing));
  // Drops up to 10 mm reach x = 2 pi r / lambda ~ 1.14e5 at 550 nm, beyond max_x = 1e5, the
  // range of forward_amplitude (cost ~ x^2).
  CHECK_FALSE(segmented_contour_extinction(table_through({{100, 1e-3}, {10000, 1e-6}}, "hail-sized"), 550e-9,
                                           kAbsorbing));
}

TEST_CASE("segmented contour: spans across rows equal one panel per row, with jumps and kinks", "[weather][segmented]") {
  // Reference: the same route with spans off (each row its own Gauss-Kronrod panels: no
  // product integration) and the axis panels in y, at 1e-11.  Cases: 150 fog-drop bins 0.2 um wide from 2 to 32 um
  // (a jump at every edge, count falling as r^-3) and an 800-row log-normal table (a kink
  // at every row), at 550 nm and 10.6 um.
  std::vector<TabulatedSegment> bins;
  for (int i = 0; i < 150; ++i) {
    const double r0 = 2e-6 + 2e-7 * i, n = 1e12 * std::pow(r0 / 2e-6, -3.0) * (1 + 0.3 * (i % 3));
    bins.push_back({r0, 2e-6 + 2e-7 * (i + 1), n, n});
  }
  const std::vector<SizeDistribution> cases = {SizeDistribution::tabulated(bins, "150 fog-drop bins"),
                                               log_normal_table(800)};
  for (const auto& d : cases)
    for (double wavelength : {550e-9, 10.6e-6}) {
      const auto m = refractive_index_table("water").at(wavelength);
      const auto spans = route(d, wavelength, m);
      SegmentedContourSettings rows;
      rows.spans = false;
      rows.sqrt_axis_panels = false;
      rows.rel_tolerance = 1e-11;
      rows.max_evaluations = 2000000;
      rows.max_seconds = 60;
      const auto reference = route(d, wavelength, m, rows);
      const double actual = std::abs(spans.extinction.value - reference.extinction.value);
      INFO(std::setprecision(13) << d.describe() << " at " << wavelength << " m: spans " << spans.extinction.value
                                 << " +- " << spans.extinction.error() << " (" << spans.evaluations
                                 << " evaluations), rows " << reference.extinction.value << " +- "
                                 << reference.extinction.error() << " (" << reference.evaluations << ")");
      CHECK(actual <= spans.extinction.error() + reference.extinction.error());
      CHECK(spans.extinction.error() <= 1.1e-9 * spans.extinction.value);
    }
}

// [slow]: 16 s under ASan; the sanitizer tree checks windows on the 10,000-row table
// (test_binned_spectra.cpp) and spans in the test above.
TEST_CASE("segmented contour: leg windows over dense bins, a jump at every edge", "[weather][segmented][slow]") {
  // 6,000 bins 1/3 nm wide from 5 to 7 um (x spacing 0.0038 at 550 nm), the count varying
  // from bin to bin and a slope inside every other one: at a loose tolerance the legs'
  // first cuts are wide enough that windows form across the jumps.  Reference: the same
  // table with spans and windows off (one panel per row, every leg up to the path, the axis
  // panels in y) at 1e-7 (at 1e-8 its rounding bound exceeds the tolerance and it runs in long
  // double, 14 s).
  std::vector<TabulatedSegment> bins;
  const int n = 6000;
  for (int i = 0; i < n; ++i) {
    const double r0 = 5e-6 + 2e-6 * i / n, r1 = 5e-6 + 2e-6 * (i + 1) / n;
    const double v = 1e12 * (1 + 0.2 * std::sin(0.7 * i));
    bins.push_back({r0, r1, v, v * (1 + 0.01 * (i % 2))});
  }
  const auto d = SizeDistribution::tabulated(bins, "6,000 dense bins");
  const auto m = refractive_index_table("water").at(550e-9);
  SegmentedContourSettings loose;
  loose.rel_tolerance = 1e-3;
  const auto windows = route(d, 550e-9, m, loose);
  SegmentedContourSettings rows;
  rows.spans = false;
  rows.sqrt_axis_panels = false;
  rows.rel_tolerance = 1e-7;
  rows.max_seconds = 60;
  const auto reference = route(d, 550e-9, m, rows);
  INFO(std::setprecision(13) << windows.extinction.value << " +- " << windows.extinction.error() << " ("
                             << windows.evaluations << " evaluations), reference " << reference.extinction.value
                             << " +- " << reference.extinction.error() << "; " << windows.method);
  CHECK(windows.method.find("windows") != std::string::npos);
  CHECK(std::abs(windows.extinction.value - reference.extinction.value) <=
        windows.extinction.error() + reference.extinction.error());
  CHECK(windows.extinction.error() <= 1e-3 * windows.extinction.value);
}

TEST_CASE("segmented contour: legs that cancel beyond double precision are taken in long double",
          "[weather][segmented]") {
  // A step of 1 % over 1e-9 um at 5 um: two kinks whose slope changes, +-1e7 times the table's
  // n / r, give legs ~1e4 times sigma_ext that cancel to the step's jump.  Splitting panels does
  // not lower the rounding bound of their S(0) in double (2.2e-10 1/m against the tolerance
  // 2.2e-12, measured), so the route repeats the run in long double.  Reference: the same
  // density with a true jump at 5 um (bins: jump legs, double), which differs from the steep
  // ramp by less than 0.005 x 1e12 m^-4 x 1e-15 m x Q_ext <= 4 x pi (5 um)^2 = 1.6e-15 1/m.
  const auto steep = table_through({{1, 1}, {5, 1}, {5 + 1e-9, 1.01}, {10, 1.01}}, "a steep step");
  const auto jump = SizeDistribution::tabulated({{1e-6, 5e-6, 1e12, 1e12}, {5e-6, 10e-6, 1.01e12, 1.01e12}}, "a jump");
  const auto m = refractive_index_table("water").at(550e-9);
  const auto a = segmented_contour_extinction(steep, 550e-9, m);
  const auto b = segmented_contour_extinction(jump, 550e-9, m);
  REQUIRE(a);
  REQUIRE(b);
  INFO(std::setprecision(13) << a->extinction.value << " +- " << a->extinction.error() << "; " << b->extinction.value
                             << " +- " << b->extinction.error() << "; " << a->method);
  CHECK(a->method.find("long double") != std::string::npos);
  CHECK(a->extinction.error() <= 1e-9 * a->extinction.value);
  CHECK(std::abs(a->extinction.value - b->extinction.value) <= a->extinction.error() + b->extinction.error() + 1.6e-15);
}
