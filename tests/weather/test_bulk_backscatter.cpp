// Backscatter, lidar ratio, bulk phase function and Legendre moments of a
// size distribution (bulk_optics.hpp): closed forms, identities between the
// quantities, and brute-force references for nearly lossless water drops.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"
#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;
namespace mie = attenuvis::mie;

namespace {
const double kPi = boost::math::constants::pi<double>();

// Constant efficiencies: every bulk quantity is a multiple of the exact
// geometric cross-section pi int r^2 n dr.
Efficiency constant_sphere(double) {
  Efficiency e{2.0, 1.5, 0.5, 0.6, 4 * kPi * 0.05, {1.0, 0.6, 0.4}, {7.0, 0.2}, {}};
  return e;
}

// Brute-force reference: the trapezoid rule in x with step h (1/h points per
// unit x) over the radii holding all but 1e-9 of the r^2 moment, accumulated
// in long double, the sphere sums split over threads (TBB).  The trapezoid, not
// Gauss-Legendre panels: Q_back's resonances narrower than the node spacing
// dominate its fine structure, and an equispaced rule samples each at a phase
// unrelated to its position, with equal weights, which averages them without
// bias; 16-point Gauss-Legendre panels at 32 points per unit x (26 per 0.8
// ripple period) left two references for radiation fog at 550 nm 1.2% apart.
// Returns sigma_ext, sigma_sca, beta_pi and the Q_sca-weighted integrals of
// p at `angles` and of chi_l up to L.
struct Reference {
  long double ext = 0, sca = 0, back = 0;
  std::vector<long double> phase, moments;
  Reference& operator+=(const Reference& o) {
    ext += o.ext;
    sca += o.sca;
    back += o.back;
    phase.resize(std::max(phase.size(), o.phase.size()), 0.0L);
    moments.resize(std::max(moments.size(), o.moments.size()), 0.0L);
    for (std::size_t i = 0; i < o.phase.size(); ++i) phase[i] += o.phase[i];
    for (std::size_t i = 0; i < o.moments.size(); ++i) moments[i] += o.moments[i];
    return *this;
  }
};
Reference brute_force(const SizeDistribution& d, double wavelength, std::complex<double> m, double h,
                      const std::vector<double>& angles = {}, int L = -1) {
  const auto sup = d.support(2.0, 1e-9);
  const double k = 2 * kPi / wavelength;
  const double xa = k * sup.breakpoints_m.front(), xb = k * sup.breakpoints_m.back();
  const long n = static_cast<long>(std::ceil((xb - xa) / h));
  const double step = (xb - xa) / n;
  mie::Extras extras;
  extras.angles_deg = angles;
  extras.coefficients = L >= 0;
  auto sum = [&](const tbb::blocked_range<long>& range, Reference acc) {
    acc.phase.resize(angles.size(), 0.0L);
    acc.moments.resize(L >= 0 ? L + 1 : 0, 0.0L);
    for (long i = range.begin(); i < range.end(); ++i) {
      const double x = xa + i * step, r = x / k;
      const long double w = ((i == 0 || i == n) ? 0.5L : 1.0L) * step * kPi * r * r * d.density(r) / k;
      const auto s = mie::scatter(x, m, extras);
      acc.ext += w * s.q.qext;
      acc.sca += w * s.q.qsca;
      acc.back += w * s.q.qback / (4 * kPi);
      if (!angles.empty()) {
        const auto sm = mie::scattering_matrix(x, s);
        for (std::size_t a = 0; a < angles.size(); ++a) acc.phase[a] += w * s.q.qsca * sm.phase[a];
      }
      if (L >= 0) {
        auto chi = mie::phase_function_moments(s, static_cast<std::size_t>(L));
        chi.resize(L + 1, 0.0);
        for (int l = 0; l <= L; ++l) acc.moments[l] += w * s.q.qsca * chi[l];
      }
    }
    return acc;
  };
  return tbb::parallel_reduce(tbb::blocked_range<long>(0, n + 1, 256), Reference{}, sum,
                              [](Reference a, const Reference& b) { return a += b; });
}

}  // namespace

TEST_CASE("constant efficiencies give the closed-form backscatter, lidar ratio and moments",
          "[weather][bulk][backscatter]") {
  // pi int r^2 n dr for the log-normal: pi N r_g^2 exp(2 ln^2 sg) (exact moment).
  const auto d = SizeDistribution::log_normal(1e8, 2e-6, 1.6);
  const double area = kPi * 1e8 * 4e-12 * std::exp(2 * std::pow(std::log(1.6), 2));
  QuadratureSettings s;
  s.backscatter = true;
  s.legendre_moments = 2;
  s.angles_deg = {0.0, 90.0};
  const BulkOptics b = integrate_bulk_optics(d, 550e-9, constant_sphere, s);
  REQUIRE(b.backscatter_computed);
  CHECK(std::abs(b.backscatter.value - 0.05 * area) <= b.backscatter.error());
  CHECK(std::abs(b.backscatter.value - 0.05 * area) / (0.05 * area) < 1e-9);
  CHECK(std::abs(b.lidar_ratio - 40.0) <= b.lidar_ratio_error);  // 2 / 0.05 sr
  CHECK(b.lidar_ratio_error < 1e-7);
  REQUIRE(b.moments.size() == 3);
  const double chi[] = {1.0, 0.6, 0.4};
  for (int l = 0; l < 3; ++l) CHECK(std::abs(b.moments[l] - chi[l]) <= b.moments_error[l] + 1e-15);
  REQUIRE(b.phase.size() == 2);
  CHECK(std::abs(b.phase[0] - 7.0) <= b.phase_error[0] + 1e-14);
  CHECK(std::abs(b.phase[1] - 0.2) <= b.phase_error[1] + 1e-15);
}

TEST_CASE("optional quantities are computed only when asked for", "[weather][bulk][backscatter]") {
  const auto d = SizeDistribution::log_normal(1e8, 2e-6, 1.6);
  const BulkOptics plain = integrate_bulk_optics(d, 550e-9, constant_sphere);
  CHECK_FALSE(plain.backscatter_computed);
  CHECK(plain.moments.empty());
  CHECK(plain.phase.empty());
  // An efficiency function that cannot supply what is asked for is an error, not a zero.
  QuadratureSettings s;
  s.legendre_moments = 8;
  CHECK_THROWS_AS(integrate_bulk_optics(d, 550e-9, constant_sphere, s), std::invalid_argument);
}

TEST_CASE("bulk backscatter, phase function and moments agree with each other (Mie)",
          "[weather][bulk][backscatter]") {
  // Radiation fog (P.1817-1 / seed Table: alpha = 6, a = 607.5, b = 3) at 1.55 um, water
  // (Hale & Querry 1973).  Identities that hold sphere by sphere hold for the bulk sums:
  // Q_back/(4 pi) = Q_sca p(pi)/(4 pi) (B&H 4.82), chi_0 = 1, chi_1 = g.
  const auto m = refractive_index_table("water").at(1.55e-6);
  QuadratureSettings s;
  s.backscatter = true;
  s.legendre_moments = 4;
  s.angles_deg = {180.0};
  const BulkOptics b = bulk_optics(preset_distribution("radiation"), 1.55e-6, m, s);
  REQUIRE(b.backscatter_computed);
  const double beta_from_phase = b.scattering.value * b.phase[0] / (4 * kPi);
  const double tol = b.backscatter.error() + b.scattering.value * b.phase_error[0] / (4 * kPi) +
                     b.phase[0] * b.scattering.error() / (4 * kPi);
  INFO(std::setprecision(10) << "beta " << b.backscatter.value << " +- " << b.backscatter.error()
                             << " from p(pi): " << beta_from_phase << " +- " << tol);
  CHECK(std::abs(b.backscatter.value - beta_from_phase) <= tol);
  CHECK(std::abs(b.moments[0] - 1.0) <= b.moments_error[0] + 1e-14);
  CHECK(std::abs(b.moments[1] - b.asymmetry) <= b.moments_error[1] + b.asymmetry_error);
}

namespace {
// How far the brute-force sums can be trusted.  Where the resonances are
// broader than the step (1.55 um: k ~ 1e-4) the two sums agree far below our
// reported error and serve as truth: `Converged` requires that.  At 550 nm
// (k = 1.96e-9) the resonances near x ~ 100 are ~1e-8 wide, far narrower than
// any affordable step, and the two sums sample them at unrelated phases: they
// disagree by ~1e-4 (beta_pi, p(180)) and ~1e-6 (chi_l), far above the 1e-6
// and 1e-8 we report.  There the comparison grants their disagreement and
// checks only agreement to that level; the finer claim rests on the pole
// analysis (bulk_optics.hpp) and on the 1.55 um cases.
enum class BruteForce { Converged, Unconverged };

// Our bulk result for `d` against two brute-force references with steps h and
// 0.6 h in x (h = 1e-3: 800 points per 0.8-period ripple).
void check_against_brute_force(const SizeDistribution& d, double wavelength, const std::vector<double>& angles,
                               int L, BruteForce kind = BruteForce::Converged, double h = 1e-3) {
  const auto m = refractive_index_table("water").at(wavelength);
  QuadratureSettings s;
  s.backscatter = true;
  s.angles_deg = angles;
  s.legendre_moments = L;
  const BulkOptics b = bulk_optics(d, wavelength, m, s);
  const Reference r1 = brute_force(d, wavelength, m, h, angles, L);
  const Reference r2 = brute_force(d, wavelength, m, 0.6 * h, angles, L);
  const bool converged = kind == BruteForce::Converged;
  const double angular = std::max(s.rel_tolerance, 1e-6);  // bulk_optics.hpp: the default angular tolerance
  INFO(std::setprecision(10) << d.describe() << " at " << wavelength << " m, " << b.evaluations << " evaluations");
  // |ours - t2| within our error (and the references' own disagreement where
  // they have not converged); our error within the tolerance asked for.
  auto check = [&](const char* name, double value, double error, double t1, double t2, double allowed) {
    const double spread = converged ? 0.0 : std::abs(t1 - t2);
    INFO(name << " " << value << " +- " << error << "; brute force " << t1 << " / " << t2 << " (allowed error "
              << allowed << ")");
    if (converged) CHECK(std::abs(t1 - t2) < 0.3 * error + 1e-15);
    CHECK(std::abs(value - t2) <= error + spread + 1e-15);
    CHECK(error <= allowed);
  };
  {
    const double t1 = static_cast<double>(r1.back), t2 = static_cast<double>(r2.back);
    INFO("beta_pi resonance part " << b.backscatter.resonance_error << ", quadrature "
                                   << b.backscatter.quadrature_error);
    check("beta_pi", b.backscatter.value, b.backscatter.error(), t1, t2, angular * b.backscatter.value);
    const double s1 = static_cast<double>(r1.ext / r1.back), s2 = static_cast<double>(r2.ext / r2.back);
    check("lidar ratio", b.lidar_ratio, b.lidar_ratio_error, s1, s2, angular * b.lidar_ratio);
  }
  for (std::size_t a = 0; a < angles.size(); ++a) {
    const double t1 = static_cast<double>(r1.phase[a] / r1.sca), t2 = static_cast<double>(r2.phase[a] / r2.sca);
    const std::string name = "p(" + std::to_string(angles[a]) + ")";
    check(name.c_str(), b.phase[a], b.phase_error[a], t1, t2, angular * b.phase[a]);
  }
  for (int l = 0; l <= L; ++l) {
    const double t1 = static_cast<double>(r1.moments[l] / r1.sca), t2 = static_cast<double>(r2.moments[l] / r2.sca);
    const std::string name = "chi_" + std::to_string(l);
    // bulk_optics.hpp: chi_l relative to max(|chi_l|, 1e-3).
    check(name.c_str(), b.moments[l], b.moments_error[l], t1, t2, angular * std::max(std::abs(t2), 1e-3));
  }
}
}  // namespace

TEST_CASE("bulk phase function at 90 deg of advection fog at 550 nm: a tolerance beyond the budget is said to be missed",
          "[weather][bulk][backscatter][advection]") {
  // Advection fog (P.1817-1 / seed Table: alpha = 3, a = 0.027, b = 0.3), water at 550 nm
  // (Hale & Querry 1973, k = 1.96e-9): resonances of every width up to x ~ 1700.  At 90 deg the
  // phase function is ~0.1 and the narrow resonances weigh most; 1e-6 of it needs more than the
  // default budget (it stops ~200 times above it after 1.1e6 evaluations).  Within a budget of
  // 5e4 evaluations the result must come back with the error it reached, larger than the
  // tolerance, and say that it missed it (bulk_optics.hpp), not claim the tolerance.
  QuadratureSettings s;
  s.angles_deg = {90.0};
  s.max_evaluations = 50000;
  const BulkOptics b =
      bulk_optics(preset_distribution("advection"), 550e-9, refractive_index_table("water").at(550e-9), s);
  INFO(b.shortfall);
  CHECK_THAT(b.shortfall, Contains("phase function at 90 deg") && Contains("not met"));
  REQUIRE(b.phase.size() == 1);
  CHECK(b.phase_error[0] > 1e-6 * b.phase[0]);
  CHECK_THAT(b.method, Contains("tolerance not met"));
}

TEST_CASE("bulk backscatter and phase function errors cover the resonances: advection fog, 1.55 um",
          "[weather][bulk][backscatter][brute][advection][slow]") {
  check_against_brute_force(preset_distribution("advection"), 1.55e-6, {180.0, 150.0, 90.0}, -1);
}

TEST_CASE("bulk Legendre moment errors cover the resonances: radiation fog, 550 nm and 1.55 um",
          "[weather][bulk][backscatter][brute][slow]") {
  // Radiation fog (alpha = 6, a = 607.5, b = 3: x < 140 at 550 nm) keeps the O(N^2) moments of
  // the brute-force sums affordable.
  check_against_brute_force(preset_distribution("radiation"), 550e-9, {180.0}, 8, BruteForce::Unconverged);
  // Without a phase function the moments' own (looser) resonance target drives the refinement.
  check_against_brute_force(preset_distribution("radiation"), 550e-9, {}, 8, BruteForce::Unconverged);
  check_against_brute_force(preset_distribution("radiation"), 1.55e-6, {180.0}, 8);
}

TEST_CASE("bulk Legendre moment errors cover the resonances: advection fog, 1.55 um, L = 64",
          "[weather][bulk][backscatter][brute][advection][slow]") {
  // Advection fog (x < 580 at 1.55 um) with the moments of the optics command's
  // L = 64: the reported error of every chi_l must cover the brute-force sums
  // (2 x ~0.6 M spheres with moments).
  check_against_brute_force(preset_distribution("advection"), 1.55e-6, {}, 64);
}

TEST_CASE("bulk scattering-matrix expansion: identities of de Rooij & van der Stap (Mie)",
          "[weather][bulk][polarised]") {
  // Radiation fog at 1.55 um (P.1817-1 / seed; water from Hale & Querry 1973).  Each sphere's
  // alpha1_l = (2l+1) chi_l, alpha1_0 = 1; alpha2, alpha3, beta1, beta2 vanish for l < 2;
  // |alpha1,4|, |beta1,2| <= 2l+1 (legendre_moments.hpp); all survive the weighted average.
  const auto m = refractive_index_table("water").at(1.55e-6);
  QuadratureSettings s;
  s.legendre_moments = 6;
  s.polarised = true;
  const BulkOptics b = mie_bulk_optics(preset_distribution("radiation"), 1.55e-6, m, s);
  const auto& e = b.expansion;
  REQUIRE(e.alpha1.size() == 7);
  REQUIRE(e.beta2.size() == 7);
  CHECK(std::abs(e.alpha1[0] - 1.0) <= b.expansion_error.alpha1[0] + 1e-14);
  for (int l = 0; l <= 6; ++l) {
    INFO("l = " << l);
    CHECK(std::abs(e.alpha1[l] - (2 * l + 1) * b.moments[l]) <= 1e-12 * (2 * l + 1));
    for (const auto* v : {&e.alpha1, &e.alpha4, &e.beta1, &e.beta2}) CHECK(std::abs((*v)[l]) <= 2 * l + 1 + 1e-12);
    CHECK(b.expansion_error.alpha2[l] >= 0);
    if (l < 2)
      for (const auto* v : {&e.alpha2, &e.alpha3, &e.beta1, &e.beta2}) CHECK(std::abs((*v)[l]) < 1e-12);
  }
  // Requested alone, nothing polarised is computed.
  s.polarised = false;
  CHECK(mie_bulk_optics(preset_distribution("radiation"), 1.55e-6, m, s).expansion.alpha1.empty());
}
