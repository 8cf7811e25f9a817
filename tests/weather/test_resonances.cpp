// Nearly non-absorbing drops: the reported error must cover the Q_ext
// resonances the quadrature cannot resolve.
#include <catch2/catch.hpp>

#include <cmath>

#include "attenuvis/mie.hpp"
#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;

namespace {
const double kPi = 3.14159265358979323846;

// Truth by brute force: trapezoid in x with step h over a narrow distribution,
// so that every resonance wider than ~h is sampled many times.
double brute_force(const SizeDistribution& d, double wavelength, std::complex<double> m, double h) {
  auto sup = d.support(2.0, 1e-14);
  double k = 2 * kPi / wavelength;
  double xa = k * sup.breakpoints_m.front(), xb = k * sup.breakpoints_m.back();
  long n = static_cast<long>(std::ceil((xb - xa) / h));
  double step = (xb - xa) / n, sum = 0;
  for (long i = 0; i <= n; ++i) {
    double x = xa + i * step, r = x / k;
    double f = attenuvis::mie::sphere(x, m).qext * kPi * r * r * d.density(r) / k;
    sum += (i == 0 || i == n) ? 0.5 * f : f;
  }
  return sum * step;
}
}  // namespace

TEST_CASE("reported error covers unresolved resonances (brute force, x ~ 35)", "[weather][resonance][slow]") {
  // Water at 550 nm (Hale & Querry 1973: m = 1.333 + 1.96e-9 i); a log-normal with sigma_g = 1.03
  // around r = 3 um puts all drops at 31 < x < 39, where Q_ext has dozens of resonances of
  // widths down to ~1e-7 in x.  Two brute-force sums with different steps agree with each other
  // far better than the reported error (checked below), so their difference from our value is
  // the true error to within that agreement.
  auto m = refractive_index_table("water").at(550e-9);
  auto d = SizeDistribution::log_normal(1e8, 3e-6, 1.03);
  auto b = bulk_optics(d, 550e-9, m);
  double truth = brute_force(d, 550e-9, m, 2e-5);
  double truth2 = brute_force(d, 550e-9, m, 1.3e-5);
  INFO("value " << b.extinction.value << " truth " << truth << " / " << truth2 << " reported error "
                << b.extinction.error() << " (resonance part " << b.extinction.resonance_error << ")");
  CHECK(std::abs(truth - truth2) < 0.1 * b.extinction.error());
  CHECK(std::abs(b.extinction.value - truth) <= b.extinction.error());
  // The resonances matter: a smooth rule's own |K - G| estimate alone would not cover this case.
  CHECK(b.extinction.resonance_error > b.extinction.quadrature_error);
}

TEST_CASE("resonance floor applies only to nearly non-absorbing spheres", "[weather][resonance]") {
  auto d = SizeDistribution::log_normal(1e8, 3e-6, 1.03);
  auto lossy = bulk_optics(d, 550e-9, {1.333, 0.01});
  CHECK(lossy.extinction.resonance_error == 0);
  CHECK(lossy.floor_panels == 0);
  auto clear = bulk_optics(d, 550e-9, {1.333, 1.96e-9});
  CHECK(clear.floor_panels > 0);
}
