// Brute-force reference values of the bulk single-scattering optics of a size
// distribution, independent of bulk_optics.hpp: composite Gauss-Legendre in x
// (8 nodes per panel of width h, panels edge to edge over the radii holding all
// but 1e-13 of the r^2 moment), every sphere by attenuvis::mie (scatter(),
// phase_function_moments(), scattering_matrix(); the core checked against its
// 50-digit referee), the sums accumulated in long double.  The same sums with
// h and h/2 are printed side by side with their relative difference: where the
// integrand's narrowest features (resonances of width ~k x / n) are resolved,
// the difference shrinks like the rule's error and bounds the error of the
// finer sum; where it does not shrink, the reference is not converged and the
// printed difference says by how much.  The omitted tails move sigma by at
// most 4 x 1e-13 x pi int r^2 n dr (Q_ext <= 4 for these spheres), the
// normalised quantities by as much relative to sigma_sca.
//
// Usage: bulk_brute_force DIST LAMBDA_NM M_RE M_IM H [L=32]
//   DIST: radiation | advection (the P.1817-1 / seed fog presets) | lognormal
//         (r_g = 1 um, sigma_g = 1.5, 100 cm^-3) | file:PATH (a size-distribution
//         CSV, distribution_file.hpp; no panel straddles a row or bin edge)
// Prints sigma_ext, sigma_sca, sigma_abs (1/m), ssa, g, beta_pi (1/(m sr)), the
// lidar ratio (sr), and unless L < 0 (efficiencies only: ~30x faster at x ~ 1000)
// chi_1..chi_L and p(theta) at 0, 30, 90, 150, 180 degrees.
// Runs on every thread TBB offers.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"
#include "attenuvis/weather.hpp"

namespace w = attenuvis::weather;
namespace mie = attenuvis::mie;

namespace {

constexpr double kPi = boost::math::constants::pi<double>();
const std::vector<double> kAngles = {0.0, 30.0, 90.0, 150.0, 180.0};

// Sums of w Q over the nodes: ext, sca, abs, g Q_sca, Q_back / 4 pi, then
// chi_l Q_sca (l = 0..L) and p(theta) Q_sca.
struct Sums {
  std::vector<long double> v;
  Sums& operator+=(const Sums& o) {
    if (v.size() < o.v.size()) v.resize(o.v.size(), 0.0L);
    for (std::size_t i = 0; i < o.v.size(); ++i) v[i] += o.v[i];
    return *this;
  }
};
enum { kExt, kSca, kAbs, kGSca, kBack, kFirstMoment };

Sums brute_force(const w::SizeDistribution& d, double wavelength, std::complex<double> m, double h, int L) {
  const auto support = d.support(2.0, 1e-13);
  const double k = 2 * kPi / wavelength;
  // Panels never straddle a breakpoint of the density (a bin edge is a jump).
  std::vector<std::pair<double, double>> panels;  // (start, width) in x
  for (std::size_t i = 0; i + 1 < support.breakpoints_m.size(); ++i) {
    const double xa = k * support.breakpoints_m[i], xb = k * support.breakpoints_m[i + 1];
    const long n = std::max(1L, static_cast<long>(std::ceil((xb - xa) / h)));
    for (long j = 0; j < n; ++j) panels.emplace_back(xa + (xb - xa) * j / n, (xb - xa) / n);
  }
  using Rule = boost::math::quadrature::gauss<long double, 8>;
  const auto& abscissa = Rule::abscissa();
  const auto& weights = Rule::weights();
  const bool angular = L >= 0;
  const std::size_t size = kFirstMoment + (angular ? static_cast<std::size_t>(L + 1) + kAngles.size() : 0);
  mie::Extras extras;
  extras.coefficients = angular;
  if (angular) extras.angles_deg = kAngles;
  // Every panel, every node pair (the 8-point rule has no centre node).
  auto sum = [&](const tbb::blocked_range<long>& range, Sums acc) {
    acc.v.resize(size, 0.0L);
    for (long p = range.begin(); p < range.end(); ++p) {
      const long double step = panels[p].second, mid = panels[p].first + 0.5L * step;
      for (std::size_t i = 0; i < abscissa.size(); ++i)
        for (int sign : {-1, 1}) {
          const long double x = mid + sign * abscissa[i] * 0.5L * step;
          const double xd = static_cast<double>(x), r = xd / k;
          const long double wx = weights[i] * 0.5L * step * kPi * r * r * d.density(r) / k;
          const auto s = mie::scatter(xd, m, extras);
          acc.v[kExt] += wx * s.q.qext;
          acc.v[kSca] += wx * s.q.qsca;
          acc.v[kAbs] += wx * s.q.qabs;
          acc.v[kGSca] += wx * s.q.g * s.q.qsca;
          acc.v[kBack] += wx * s.q.qback / (4 * kPi);
          if (!angular) continue;
          std::vector<double> chi = mie::phase_function_moments(s, static_cast<std::size_t>(L));
          chi.resize(static_cast<std::size_t>(L + 1), 0.0);
          for (int l = 0; l <= L; ++l) acc.v[kFirstMoment + l] += wx * s.q.qsca * chi[l];
          const auto matrix = mie::scattering_matrix(xd, s);
          for (std::size_t a = 0; a < kAngles.size(); ++a)
            acc.v[kFirstMoment + L + 1 + a] += wx * s.q.qsca * matrix.phase[a];
        }
    }
    return acc;
  };
  return tbb::parallel_reduce(tbb::blocked_range<long>(0, static_cast<long>(panels.size()), 64), Sums{}, sum,
                              [](Sums a, const Sums& b) { return a += b; });
}

w::SizeDistribution distribution(const std::string& name) {
  if (name.rfind("file:", 0) == 0) return w::read_distribution_csv(name.substr(5));
  if (name == "lognormal") return w::SizeDistribution::log_normal(1e8, 1e-6, 1.5);
  return w::preset_distribution(name);
}

void row(const char* name, long double a, long double b) {
  const long double diff = std::fabs(a - b) / std::max(std::fabs(b), 1e-300L);
  std::printf("%-12s %.15Lg %.15Lg %.2Le\n", name, a, b, diff);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: bulk_brute_force DIST LAMBDA_NM M_RE M_IM H [L=32]\n");
    return 2;
  }
  const w::SizeDistribution d = distribution(argv[1]);
  const double wavelength = std::atof(argv[2]) * 1e-9;
  const std::complex<double> m(std::atof(argv[3]), std::atof(argv[4]));
  const double h = std::atof(argv[5]);
  const int L = argc > 6 ? std::atoi(argv[6]) : 32;
  const Sums coarse = brute_force(d, wavelength, m, h, L), fine = brute_force(d, wavelength, m, 0.5 * h, L);
  std::printf("# %s at %g nm, m = %.17g%+.17gi, composite 8-point Gauss-Legendre, h = %g and %g in x\n", argv[1],
              wavelength * 1e9, m.real(), m.imag(), h, 0.5 * h);
  std::printf("# quantity   h            h/2          |difference| / value\n");
  const auto& c = coarse.v;
  const auto& f = fine.v;
  row("sigma_ext", c[kExt], f[kExt]);
  row("sigma_sca", c[kSca], f[kSca]);
  row("sigma_abs", c[kAbs], f[kAbs]);
  row("ssa", c[kSca] / c[kExt], f[kSca] / f[kExt]);
  row("g", c[kGSca] / c[kSca], f[kGSca] / f[kSca]);
  row("beta_pi", c[kBack], f[kBack]);
  row("lidar_ratio", c[kExt] / c[kBack], f[kExt] / f[kBack]);
  if (L < 0) return 0;
  for (int l = 1; l <= L; ++l) {
    const std::string name = "chi_" + std::to_string(l);
    row(name.c_str(), c[kFirstMoment + l] / c[kSca], f[kFirstMoment + l] / f[kSca]);
  }
  for (std::size_t a = 0; a < kAngles.size(); ++a) {
    const std::string name = "p(" + std::to_string(static_cast<int>(kAngles[a])) + ")";
    const std::size_t i = kFirstMoment + L + 1 + a;
    row(name.c_str(), c[i] / c[kSca], f[i] / f[kSca]);
  }
  return 0;
}
