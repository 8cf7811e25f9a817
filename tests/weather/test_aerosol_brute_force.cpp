// The reported errors of the aerosol integrals against brute-force sums: for
// every OPAC component at 0 % and (the hygroscopic ones) 99 % RH, at 355, 550,
// 1064 and 10,600 nm, the certified sigma_ext, sigma_sca, sigma_abs and g
// must lie within their reported errors of a Simpson sum in ln r over the
// whole cut log-normal [Rmin, Rmax], accumulated in long double with many more
// points than the quadrature uses.  Two sums, the second with 4x the points,
// bound the reference's own error: they must agree within the reported error
// (the reference resolves what we claim), and ours must lie within the
// reported error of the finer one, widened by their difference.  For the
// smooth integrands of absorbing particles that difference is ~1e-16 relative
// and the test is our error alone.  Nearly lossless droplets carry resonances
// that the quadrature resolves to ~1e-10 relative; there the reference is
// refined until it resolves them too, and where no affordable sum does (the
// humid sea salt and sulfate at 355 and 550 nm, x up to 1800), sigma_ext is
// checked against the segmented contour integral instead (see check_component).  A
// representative subset runs by default; all 56 cases are [slow].
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <vector>
#include <cmath>
#include <iomanip>
#include <string>

#include <boost/math/constants/constants.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"
#include "attenuvis/weather.hpp"
#include "attenuvis/weather/segmented_contour.hpp"

using namespace attenuvis;
using namespace attenuvis::weather;

namespace {

const double kPi = boost::math::constants::pi<double>();

constexpr long kChunk = 2048;  // spheres per mie::spheres call
// The finest reference sum: ~2 s of 2 cores at x ~ 300 (mie::spheres).
constexpr long kMaxReferencePoints = 6000000;

struct Sums {
  long double ext = 0, sca = 0, abs = 0, gsca = 0;
  Sums& operator+=(const Sums& o) {
    ext += o.ext;
    sca += o.sca;
    abs += o.abs;
    gsca += o.gsca;
    return *this;
  }
};

// Simpson's rule in u = ln r on [ln Rmin, ln Rmax] with n (even) intervals:
// the integrand r n(r) pi r^2 Q dr/du is smooth inside and the cut-offs are
// the ends, where it has not died away for the smallest components (soot's
// Rmin = 5 nm lies 2.6 standard deviations below its r^2 median): the
// trapezoid's h^2 end error (2e-10 relative at 60,000 points) would exceed the
// reported errors, Simpson's h^4 term does not.  Ripple of period 0.8 in x
// asks for some 16 points per period at the largest x (points_for).
Sums simpson(const SizeDistribution& d, const LogNormal& l, double wavelength, std::complex<double> m, long n) {
  const double k = 2 * kPi / wavelength;
  const double ua = std::log(l.r_min_m), ub = std::log(l.r_max_m), h = (ub - ua) / n;
  mie::SpheresOptions one_thread;
  one_thread.threads = 1;  // the chunks already run in parallel
  auto body = [&](const tbb::blocked_range<long>& range, Sums acc) {
    // A chunk's spheres at once (mie::spheres: vector lanes, the same values as mie::sphere).
    std::vector<double> r(static_cast<std::size_t>(range.size())), x(r.size());
    std::vector<mie::Efficiencies<double>> q(r.size());
    for (long i = range.begin(); i < range.end(); ++i) {
      r[i - range.begin()] = std::exp(ua + i * h);
      x[i - range.begin()] = k * r[i - range.begin()];
    }
    const std::size_t count = static_cast<std::size_t>(range.end() - range.begin());
    if (!mie::spheres(x.data(), m, count, q.data(), one_thread).empty()) std::abort();
    for (long i = range.begin(); i < range.end(); ++i) {
      const std::size_t j = static_cast<std::size_t>(i - range.begin());
      const long double weight = (i == 0 || i == n) ? 1.0L : (i % 2 == 1 ? 4.0L : 2.0L);
      const long double w = weight * h / 3 * r[j] * kPi * r[j] * r[j] * d.density(r[j]);
      acc.ext += w * q[j].qext;
      acc.sca += w * q[j].qsca;
      acc.abs += w * q[j].qabs;
      acc.gsca += w * q[j].g * q[j].qsca;
    }
    return acc;
  };
  return tbb::parallel_reduce(tbb::blocked_range<long>(0, n + 1, kChunk), Sums{}, body,
                              [](Sums a, const Sums& b) { return a += b; });
}

long points_for(const LogNormal& l, double wavelength) {
  const double x_max = 2 * kPi * l.r_max_m / wavelength;
  const double span = std::log(l.r_max_m / l.r_min_m);
  return 2 * std::max(20000L, static_cast<long>(8 * span * x_max / 0.8));  // even
}

void check_component(AerosolComponent c, double rh, double wavelength) {
  const AerosolPopulation p = component_populations(c, rh, HumidityRule::kappa).front();
  const SizeDistribution d = population_distribution(p, 1.0);
  const LogNormal& l = std::get<LogNormal>(d.form());
  const std::complex<double> m = p.index_at(wavelength);
  // What the aerosol layer reports for one particle per cm^3 of this population (its quadrature
  // and the efficiencies' accuracy, aerosol_optics.hpp).
  const AerosolCondition one{std::nullopt, {{c, 1.0}}, rh, HumidityRule::kappa, AsGiven{}};
  const BulkOptics b = aerosol_optics(one, wavelength, Settings{}, OpticsRequest{false, -1, {}, false}).bulk;
  long n = points_for(l, wavelength);
  Sums coarse = simpson(d, l, wavelength, m, n), fine = simpson(d, l, wavelength, m, 4 * n);
  // Absorbing particles (k >= 1e-3, resonance_free_k in weather/src/resonance.hpp) have smooth
  // integrands: the ripple rule (points_for) resolves them, and the two sums must agree within
  // every reported error.  Nearly lossless droplets carry resonances down to ~k x wide, which the
  // quadrature resolves (bulk_optics.hpp) and equispaced sums do not: there the reference is
  // refined 4x at a time while it does not resolve the reported errors, up to kMaxReferencePoints
  // (suso at 99 % RH, 1064 nm: the spreads of sigma_ext go 5.6e-15, 9.4e-16, 3.8e-17 against an
  // error of 2.6e-16).  Where it then resolves them, it is checked as for absorbing particles;
  // where it does not (sea salt at 99 % at 550 nm: the two finest sums give sigma_abs 3.0836 and
  // 3.0855e-12 1/m, rising towards the resolved 3.1210e-12 +- 3.9e-15), sigma_ext alone is
  // checked, against the segmented contour integral (segmented_contour.hpp), whose path above the axis
  // meets no resonance; the fogs' sigma_abs, beta_pi and chi_l are checked where sums converge in
  // test_bulk_accuracy.cpp.
  const bool lossless = m.imag() < 1e-3;
  // Resolved: the two sums' spread within half of every reported error,
  // the spread shrunk by `factor` first.
  const auto resolves = [&b](const Sums& s1, const Sums& s2, double factor = 1) {
    return std::abs(static_cast<double>(s1.ext - s2.ext)) / factor <= 0.5 * b.extinction.error() &&
           std::abs(static_cast<double>(s1.sca - s2.sca)) / factor <= 0.5 * b.scattering.error() &&
           std::abs(static_cast<double>(s1.abs - s2.abs)) / factor <= 0.5 * b.absorption.error() &&
           std::abs(static_cast<double>(s1.gsca / s1.sca - s2.gsca / s2.sca)) / factor <= 0.5 * b.asymmetry_error;
  };
  // Each refinement divides Simpson's error by ~16 once the peaks are
  // resolved (h^4); it falls faster only while the step crosses the widths of
  // the peaks.  A spread that the refinements left could not close even at
  // 256 per step goes straight to the fallback below rather than to
  // kMaxReferencePoints (the reference's budget, not a check, is at stake).
  const auto reachable = [&](long points) {
    double factor = 1;
    for (long next = 16 * points; next <= kMaxReferencePoints; next *= 4) factor *= 256;
    return resolves(coarse, fine, factor);
  };
  while (lossless && !resolves(coarse, fine) && 16 * n <= kMaxReferencePoints && reachable(n)) {
    n *= 4;
    coarse = fine;
    fine = simpson(d, l, wavelength, m, 4 * n);
  }
  INFO(std::setprecision(12) << p.describe() << " at " << wavelength * 1e9 << " nm, m = " << m << ", " << b.evaluations
                             << " evaluations against " << n << " and " << 4 * n << " points");
  const auto check = [](const char* what, double ours, double error, long double t1, long double t2) {
    INFO(what << ": " << ours << " +- " << error << ", brute force " << static_cast<double>(t1) << " / "
              << static_cast<double>(t2));
    const double spread = std::abs(static_cast<double>(t1 - t2));
    CHECK(spread <= error);
    CHECK(std::abs(ours - static_cast<double>(t2)) <= error + spread);
  };
  if (lossless && !resolves(coarse, fine)) {
    // The cut log-normal is piecewise analytic: the segmented contour, with a
    // vertical leg at each cut (segmented_contour.hpp).
    SegmentedContourSettings cs;
    cs.rel_tolerance = 1e-11;
    cs.truncated_log_normal = true;
    const auto exact = segmented_contour_extinction(d, wavelength, m, cs);
    REQUIRE(exact);
    INFO(std::setprecision(15) << "sigma_ext " << b.extinction.value << " +- " << b.extinction.error() << ", contour "
                               << exact->extinction.value << " +- " << exact->extinction.error());
    CHECK(std::abs(b.extinction.value - exact->extinction.value) <= b.extinction.error() + exact->extinction.error());
    return;
  }
  check("sigma_ext", b.extinction.value, b.extinction.error(), coarse.ext, fine.ext);
  check("sigma_sca", b.scattering.value, b.scattering.error(), coarse.sca, fine.sca);
  check("sigma_abs", b.absorption.value, b.absorption.error(), coarse.abs, fine.abs);
  check("g", b.asymmetry, b.asymmetry_error, coarse.gsca / coarse.sca, fine.gsca / fine.sca);
}

const double kWavelengths[] = {355e-9, 550e-9, 1064e-9, 10.6e-6};

}  // namespace

TEST_CASE("aerosol errors cover brute-force sums: a representative subset", "[weather][aerosol][brute]") {
  check_component(AerosolComponent::waso, 0, 550e-9);
  check_component(AerosolComponent::waso, 99, 10.6e-6);
  check_component(AerosolComponent::soot, 0, 355e-9);
  check_component(AerosolComponent::inso, 0, 1064e-9);
  check_component(AerosolComponent::ssam, 0, 1064e-9);  // nearly lossless: the reference refined once
}

TEST_CASE("aerosol errors cover brute-force sums: every component at 0 % and 99 %, four wavelengths",
          "[weather][aerosol][brute][slow]") {
  for (const AerosolComponentInfo& ci : aerosol_components())
    for (double rh : {0.0, 99.0}) {
      if (rh > 0 && !ci.hygroscopic) continue;
      for (double w : kWavelengths) check_component(ci.id, rh, w);
    }
}
