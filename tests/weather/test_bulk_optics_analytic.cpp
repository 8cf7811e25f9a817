// The bulk-optics quadrature against analytic efficiencies, whose integrals
// are known in closed form or by an independent double-exponential rule.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {
const double kPi = boost::math::constants::pi<double>();

// Anomalous diffraction (van de Hulst 1957, Sec. 11.22), non-absorbing:
// Q_ext = 2 - (4/rho) sin rho + (4/rho^2)(1 - cos rho), rho = 2 x (n - 1).
double q_ada(double x, double n = 1.33) {
  double rho = 2 * x * (n - 1);
  if (rho < 1e-3) return rho * rho / 2;  // series: Q = rho^2/2 + O(rho^4)
  return 2 - 4 / rho * std::sin(rho) + 4 / (rho * rho) * (1 - std::cos(rho));
}
Efficiency ada(double x) { return {q_ada(x), q_ada(x), 0.0, 0.8, 0.0, {}, {}, {}}; }
Efficiency two(double) { return {2.0, 2.0, 0.0, 0.5, 0.0, {}, {}, {}}; }

// Independent reference: the composite trapezoid rule in u = ln r over the
// range holding all but 1e-16 of the weight.  For a smooth integrand that
// vanishes (to 1e-16) at both ends it converges faster than any power of the
// step (Trefethen & Weideman, SIAM Rev. 56, 385 (2014)); 4e5 steps put >= 40
// points in every ADA ripple period for these cases (checked: 1e5 and 4e6 steps
// agree to 12 digits for advection fog).
double reference(const SizeDistribution& d, double wavelength, double lo, double hi) {
  double k = 2 * kPi / wavelength, a = std::log(lo), b = std::log(hi);
  const long n = 400000;
  double h = (b - a) / n, sum = 0;
  for (long i = 0; i <= n; ++i) {
    double r = std::exp(a + i * h);
    double f = r * q_ada(k * r) * kPi * r * r * d.density(r);
    sum += (i == 0 || i == n) ? 0.5 * f : f;
  }
  return sum * h;
}
}  // namespace

TEST_CASE("Q = 2 gives twice the geometric cross-section (closed form)", "[weather][quadrature]") {
  auto d = preset_distribution("advection");
  auto b = integrate_bulk_optics(d, 550e-9, two);
  // 2 pi a Gamma(6)/b^6 um^2 cm^-3 = 2 pi 0.027 * 120 / 0.3^6 * 1e-6 1/m.
  double exact = 2 * kPi * 0.027 * 120 / std::pow(0.3, 6) * 1e-6;
  CHECK(std::abs(b.extinction.value - exact) <= b.extinction.error());
  CHECK(std::abs(b.extinction.value - exact) / exact < 1e-9);
  CHECK(b.extinction.error() / exact < 2e-9);
  CHECK(b.albedo == Approx(1.0));
  CHECK(b.asymmetry == Approx(0.5));
}

TEST_CASE("one-bin table integrates exactly", "[weather][quadrature][file]") {
  auto d = read_distribution_csv(std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/one_bin.csv");
  auto b = integrate_bulk_optics(d, 550e-9, two);
  // 2 pi * 100 cm^-3 (10.5^3 - 9.5^3)/3 um^2 (uniform dN/dr over a 1 um bin).
  double exact = 2 * kPi * 100 * (std::pow(10.5, 3) - std::pow(9.5, 3)) / 3 * 1e-6;
  CHECK(b.extinction.value == Approx(exact).epsilon(1e-12));
  CHECK(b.extinction.tail_error == 0);
}

TEST_CASE("anomalous-diffraction ripple: reported error bounds the true error", "[weather][quadrature]") {
  struct Case { const char* name; SizeDistribution d; };
  std::vector<Case> cases = {
      {"advection fog", preset_distribution("advection")},
      {"radiation fog", preset_distribution("radiation")},
      {"log-normal sigma_g = 3", SizeDistribution::log_normal(1e8, 2e-6, 3.0)},
      {"near-monodisperse gamma = 60", SizeDistribution::modified_gamma_um(1.0, 4.0, 1e-30, 60.0)},
  };
  for (auto& c : cases) {
    INFO(c.name);
    for (double tol : {1e-6, 1e-9}) {
      QuadratureSettings s;
      s.rel_tolerance = tol;
      auto b = integrate_bulk_optics(c.d, 550e-9, ada, s);
      auto sup = c.d.support(2.0, 1e-16);
      double ref = reference(c.d, 550e-9, sup.breakpoints_m.front(), sup.breakpoints_m.back());
      INFO("tol " << tol << " value " << b.extinction.value << " ref " << ref << " err " << b.extinction.error());
      CHECK(std::abs(b.extinction.value - ref) <= b.extinction.error() + 1e-13 * ref);
      CHECK(b.extinction.error() <= 2 * tol * ref);
    }
  }
}

TEST_CASE("tolerance that cannot be met fails naming the integral", "[weather][quadrature]") {
  QuadratureSettings s;
  s.max_evaluations = 100;
  s.rel_tolerance = 1e-12;
  CHECK_THROWS_WITH(integrate_bulk_optics(SizeDistribution::log_normal(1e8, 2e-6, 3.0), 550e-9, ada, s),
                    Contains("sigma_") && Contains("not met"));
}

TEST_CASE("divergent integrals fail with a reason", "[weather][quadrature]") {
  // n ~ r^-4 near 0: int r^2 n dr diverges at r -> 0.
  CHECK_THROWS_WITH(integrate_bulk_optics(SizeDistribution::modified_gamma_um(1.0, -4.0, 1.0), 550e-9, two),
                    Contains("diverges"));
}
