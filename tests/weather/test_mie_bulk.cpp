// Bulk optics with Lorenz-Mie efficiencies: the seed paper's fog values,
// strongly absorbing drops at 10.6 um, and rain.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "attenuvis/mie.hpp"
#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;

namespace {
const double kPi = boost::math::constants::pi<double>();

// Independent reference: composite trapezoid in u = ln r with Mie at every
// node (spectrally accurate for a smooth integrand vanishing at both ends).
double trapezoid_ln_r(const SizeDistribution& d, double wavelength, std::complex<double> m, long steps) {
  auto sup = d.support(2.0, 1e-15);
  double a = std::log(sup.breakpoints_m.front()), b = std::log(sup.breakpoints_m.back()), h = (b - a) / steps;
  double k = 2 * kPi / wavelength, sum = 0;
  for (long i = 0; i <= steps; ++i) {
    double r = std::exp(a + i * h);
    double f = r * kPi * r * r * d.density(r) * attenuvis::mie::sphere(k * r, m).qext;
    sum += (i == 0 || i == steps) ? 0.5 * f : f;
  }
  return sum * h;
}
// For a bin (integrand not vanishing at the ends): Boost.Math's own recursive
// adaptive Gauss-Kronrod in r (a different code path from ours, in r not ln r).
double boost_gk_r(const SizeDistribution& d, double wavelength, std::complex<double> m, double lo, double hi) {
  double k = 2 * kPi / wavelength;
  auto f = [&](double r) { return kPi * r * r * d.density(r) * attenuvis::mie::sphere(k * r, m).qext; };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, lo, hi, 8, 1e-13);
}
}  // namespace

TEST_CASE("seed paper fog sigma at 550 nm", "[weather][mie][seed][slow]") {
  // Seed paper Sec. Fog: "At 550(nm) sigma = 0.02874311 m^-1 for Heavy Advection Fog and
  // sigma = 0.00863808 m^-1 for Moderate Radiation Fog".  The seed does not state its water
  // index; we use Hale & Querry (1973), m(550 nm) = 1.333 + 1.96e-9 i.  Our values differ
  // from the seed's by 1.3e-4 (advection) and 5.3e-4 (radiation) relative, far more than our
  // error estimate (contour integral, < 1e-9 relative) and more than changing the index
  // within 1.330-1.335 or to Segelstein (1981) moves them; fixed-step quadratures of the
  // same integral err by that much (reproduce: weather_fog_seed_quadrature).  The check is
  // therefore agreement to 1e-3 relative (the seed's 4th digit), with our error below 2e-4.
  Settings s;
  s.rel_tolerance = 1e-6;
  // (advection, ~3 s, is in the [slow] test below.)
  for (auto [cond, seed] : {std::pair<const char*, double>{"fog:radiation", 0.00863808}}) {
    INFO(cond);
    auto r = sigma(parse_condition(cond), 550e-9, s);
    INFO("sigma " << r.per_m << " +- " << r.error_per_m);
    CHECK(std::abs(r.per_m - seed) <= 1e-3 * seed);
    CHECK(r.error_per_m < 2e-4 * r.per_m);
  }
}

TEST_CASE("seed fog at the default tolerance 1e-9", "[weather][mie][seed][slow]") {
  Settings s;
  auto r = sigma(parse_condition("fog:advection"), 550e-9, s);
  CHECK(std::abs(r.per_m - 0.02874311) <= 1e-3 * 0.02874311);
  CHECK(r.error_per_m < 1e-4 * r.per_m);
}

TEST_CASE("strongly absorbing drops at 10.6 um: error bounds the true error", "[weather][mie]") {
  // Water at 10.6 um (Hale & Querry 1973): m ~ 1.178 + 0.0715i; no resonances, so the
  // adaptive rule must meet 1e-9 and its error must bound the dense-trapezoid reference.
  auto m = refractive_index_table("water").at(10.6e-6);
  CHECK(m.imag() > 0.05);
  for (const char* preset : {"advection", "radiation"}) {
    INFO(preset);
    auto d = preset_distribution(preset);
    auto b = bulk_optics(d, 10.6e-6, m);
    double ref = trapezoid_ln_r(d, 10.6e-6, m, 5000);
    CHECK(b.extinction.resonance_error == 0);
    CHECK(std::abs(b.extinction.value - ref) <= b.extinction.error() + 1e-13 * ref);
    CHECK(b.extinction.error() < 2e-9 * ref);
    CHECK(b.absorption.value > 0.3 * b.extinction.value);  // strongly absorbing
    CHECK(b.albedo == Approx(b.scattering.value / b.extinction.value));
  }
}

TEST_CASE("one-bin table with Mie", "[weather][mie][file]") {
  auto d = read_distribution_csv(std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/one_bin.csv");
  auto m = std::complex<double>(1.33, 0.01);  // absorbing enough to have no resonance floor
  auto b = bulk_optics(d, 550e-9, m);
  auto edges = d.support(2.0, 0.5).breakpoints_m;  // the bin edges as stored (9.5e-6 * 1e-6 rounding)
  double ref = boost_gk_r(d, 550e-9, m, edges.front(), edges.back());
  CHECK(std::abs(b.extinction.value - ref) <= b.extinction.error() + 1e-12 * ref);
}

TEST_CASE("rain by Mie over Marshall-Palmer", "[weather][mie][rain][slow]") {
  // Geometric-optics limit: Q_ext -> 2, sigma -> 2 pi int r^2 n dr = pi N0 / Lambda^3 (D in mm),
  // Marshall & Palmer (1948).  Mie adds the x^-2/3 edge term: a few per mille at 1.55 um.
  Settings s;
  s.rel_tolerance = 1e-6;
  const auto r = sigma(parse_condition("rain:8:mie"), 1.55e-6, s);
  const double lambda = 4.1 * std::pow(8.0, -0.21);
  const double geometric = kPi * 8000 / std::pow(lambda, 3) * 1e-6;
  CHECK(r.per_m > geometric);
  CHECK(r.per_m < 1.01 * geometric);
  // The contour of the analytic families reaches x = 2.4e4 here (6.8e4 at
  // 550 nm): the requested tolerance holds (the real axis reported ~0.7 %,
  // its large-x bound).
  CHECK(r.error_per_m > 0);
  CHECK(r.error_per_m <= s.rel_tolerance * r.per_m);
  CHECK(r.note.find("contour") != std::string::npos);
  // Two independent routes to one integral: the contour above the axis and
  // the real-axis quadrature (Gauss-Kronrod in ln r, large-x expansion above
  // x = 1e4, bulk_optics.hpp) agree within their errors.
  const auto c = std::get<MieCondition>(parse_condition("rain:8:mie"));
  const std::complex<double> m = condition_refractive_index(c, 1.55e-6, s);
  QuadratureSettings q;
  q.rel_tolerance = s.rel_tolerance;
  q.asymptotic_x = s.rain_asymptotic_x;
  const auto axis = integrate_bulk_optics(condition_distribution(c), 1.55e-6, mie_efficiency_batch(m), q, m);
  INFO("contour " << r.per_m << " +- " << r.error_per_m << ", real axis " << axis.extinction.value << " +- "
                  << axis.extinction.error());
  CHECK(std::abs(r.per_m - axis.extinction.value) <= r.error_per_m + axis.extinction.error());
}
