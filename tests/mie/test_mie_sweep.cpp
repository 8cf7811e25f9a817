// Dense sweeps in x for real m (k = 0): every result finite, and agreement
// with the 50-digit referee (attenuvis/mie/referee.hpp: the same series in
// cpp_bin_float_50 for exactly the double inputs) within
//     |q − q_ref| <= max(1e-10 |q_ref|, 1e-14 Qext_ref)
// for Qext, Qsca, Qabs, g and Qback at the points most at risk.
//
// Points at risk (trap sin-zero, mie/src/series.hpp): the doubles
// nearest x = jπ, where ψ₀(x) = sin x is ~1e-16..1e-18 and the downward
// recurrence forms 1/y₀ = ψ₀/ψ₁ by cancellation.  The midpoint grid
// x = 2π(i + ½)·0.1/0.55, i = 0..1412 (the report's fixed-step size
// quadrature for r = 0.1 µm steps at λ = 0.55 µm) hits them at i ≡ 5 mod 11:
// x = 182.21237390820801 (i = 159) has sin x = 2.5e-18 (mpmath), and gave
// NaN Qext and infinite Qback before ψ₁ was formed without dividing by sin x.
#include <catch2/catch.hpp>

#include <boost/math/constants/constants.hpp>
#include <cmath>
#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/referee.hpp"
#include "attenuvis/mie/spheres.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

const double kPi = boost::math::constants::pi<double>();

// The report's midpoint grid.
std::vector<double> midpoint_grid() {
  std::vector<double> xs;
  for (int i = 0; i <= 1412; ++i) xs.push_back(2 * kPi * (i + 0.5) * 0.1 / 0.55);
  return xs;
}

// The double nearest jπ (jπ formed in long double, 64-bit significand, then
// rounded once), for j = 1 .. while jπ <= x_max.
std::vector<double> multiples_of_pi(double x_max) {
  std::vector<double> xs;
  const long double pi = boost::math::constants::pi<long double>();
  for (int j = 1; static_cast<double>(j * pi) <= x_max; ++j) xs.push_back(static_cast<double>(j * pi));
  return xs;
}

// `count` x log-spaced over [lo, hi].
std::vector<double> log_spaced(double lo, double hi, int count) {
  std::vector<double> xs;
  for (int i = 0; i < count; ++i) xs.push_back(lo * std::pow(hi / lo, double(i) / (count - 1)));
  return xs;
}

bool all_finite(const mie::Efficiencies<double>& q) {
  return std::isfinite(q.qext) && std::isfinite(q.qsca) && std::isfinite(q.qabs) && std::isfinite(q.qback) &&
         std::isfinite(q.g) && std::isfinite(q.qpr);
}

// Largest of |q − q_ref| / max(1e-10 |q_ref|, 1e-14 Qext_ref) over the five
// quantities (<= 1 meets the requirement); `report` gets all values.
double referee_error(double x, cd m, std::string& report) {
  const auto q = mie::sphere(x, m);
  const auto r = mie::sphere_referee(x, m);
  const double qext = r.qext.convert_to<double>();
  const double got[5] = {q.qext, q.qsca, q.qabs, q.g, q.qback};
  const double ref[5] = {qext, r.qsca.convert_to<double>(), r.qabs.convert_to<double>(), r.g.convert_to<double>(),
                         r.qback.convert_to<double>()};
  const char* names[5] = {"qext", "qsca", "qabs", "g", "qback"};
  std::ostringstream os;
  os.precision(17);
  double worst = 0;
  for (int i = 0; i < 5; ++i) {
    const double allowed = std::max(1e-10 * std::abs(ref[i]), 1e-14 * std::abs(qext));
    const double e = std::isfinite(got[i]) ? std::abs(got[i] - ref[i]) / allowed : INFINITY;
    worst = std::max(worst, e);
    os << names[i] << " " << got[i] << " ref " << ref[i] << " (" << e << ")  ";
  }
  report = os.str();
  return worst;
}

void check_referee(double x, cd m) {
  std::string report;
  const double e = referee_error(x, m, report);
  INFO("x = " << x << " m = " << m << ": " << report);
  CHECK(e <= 1.0);
}

// sphere() and spheres() (the 8-lane batch) at every x: finite, and the batch
// bit for bit equal to sphere() (spheres.hpp promises the same operations).
void check_finite_sweep(const std::vector<double>& xs, cd m) {
  std::vector<mie::Efficiencies<double>> batch(xs.size());
  mie::SpheresOptions opt;
  opt.threads = 1;
  REQUIRE(mie::spheres(xs.data(), m, xs.size(), batch.data(), opt).empty());
  std::size_t bad = 0, differ = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const auto q = mie::sphere(xs[i], m);
    if (!all_finite(q) || !all_finite(batch[i])) {
      if (++bad <= 5) UNSCOPED_INFO("non-finite at x = " << xs[i] << " m = " << m);
    } else if (q.qext != batch[i].qext || q.qback != batch[i].qback || q.g != batch[i].g) {
      if (++differ <= 5) UNSCOPED_INFO("spheres() != sphere() at x = " << xs[i] << " m = " << m);
    }
  }
  CHECK(bad == 0);
  CHECK(differ == 0);
}

}  // namespace

TEST_CASE("sweep: the midpoint size grid with m = 1.33 is finite everywhere", "[mie][sweep]") {
  check_finite_sweep(midpoint_grid(), cd(1.33, 0));
}

TEST_CASE("sweep: real m, x = 0.1..2000 and every x = jpi, finite everywhere", "[mie][sweep]") {
  std::vector<double> xs = log_spaced(0.1, 2000, 1500);
  for (double x : multiples_of_pi(2000)) xs.push_back(x);
  for (double n : {1.33, 1.5, 2.0, 1.0001}) check_finite_sweep(xs, cd(n, 0));
}

TEST_CASE("trap sin-zero: x nearest to j pi against the referee", "[mie][trap][sweep]") {
  // The failing grid point, its neighbours in the grid and in the doubles.
  const double x0 = 182.21237390820801;
  for (double x : {x0, std::nextafter(x0, 0.0), std::nextafter(x0, 1e3), 2 * kPi * 158.5 * 0.1 / 0.55,
                   2 * kPi * 159.5 * 0.1 / 0.55})
    check_referee(x, cd(1.33, 0));
  // Other grid points at x ≈ 2jπ (|sin x| = 1e-15 .. 4e-14, not exact zeros).
  for (int i : {5, 82, 170, 588, 1402}) check_referee(2 * kPi * (i + 0.5) * 0.1 / 0.55, cd(1.33, 0));
  // The doubles nearest jπ, for the other real m (and one weakly absorbing).
  const std::vector<double> pis = multiples_of_pi(2000);
  for (std::size_t j : {1u, 2u, 7u, 31u, 58u, 200u, 600u})
    for (cd m : {cd(1.5, 0), cd(2.0, 0), cd(1.0001, 0), cd(1.33, 1e-8)}) check_referee(pis[j - 1], m);
}

TEST_CASE("trap sin-zero: every x = 2j pi of the midpoint grid against the referee", "[mie][trap][sweep][slow]") {
  const std::vector<double> grid = midpoint_grid();
  for (std::size_t i = 5; i < grid.size(); i += 11)
    for (cd m : {cd(1.33, 0), cd(1.5, 0), cd(2.0, 0), cd(1.0001, 0)}) check_referee(grid[i], m);
}
