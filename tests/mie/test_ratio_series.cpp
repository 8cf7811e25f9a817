// The power-series tables of small spheres (mie/ratio_series.hpp) against an
// independent computation: the downward recurrences of log_derivative.hpp run
// in x87 extended precision from Lentz's continued fraction (yₙ(x), yₙ(mx),
// δₙ) and the upward Hankel recurrence (ρₙ), with Rₙ and 1/|ξₙ|² as their
// running products (series.hpp's block_inputs).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <vector>

#include "attenuvis/mie/ratio_series.hpp"
#include "attenuvis/mie/series.hpp"

namespace {

using namespace attenuvis::mie::detail;
using C = std::complex<double>;
using LC = std::complex<long double>;

struct Reference {
  std::vector<long double> y, s;
  std::vector<LC> rho, w, R;
};

Reference extended_reference(double x, C m, std::size_t N, Slot slot) {
  const LC ml(m.real(), m.imag());
  const ScaledInverse<long double> over_x(x);
  const ScaledInverseComplex<long double, LC> over_z(x, ml);
  std::vector<long double> y;
  std::vector<LC> rho, w;
  std::vector<unsigned char> is_value;
  downward_ratios<long double, LC>(over_x, over_z, ml, N, slot, y, rho, w, is_value, 0);
  Reference r{y, std::vector<long double>(N + 1), rho, w, std::vector<LC>(N + 1)};
  // R₁ = ρ₁ ψ₁/ξ₀ with 1/ξ₀ = sin x + i cos x, then Rₙ = Rₙ₋₁ ρₙ yₙ₋₁; sₙ = Π |ρₖ|².
  const long double xl = x, sx = std::sin(xl), cx = std::cos(xl), psi1 = sx * y[0];
  LC R(sx * psi1, cx * psi1);
  long double s = 1;
  for (std::size_t n = 1; n <= N; ++n) {
    R = n == 1 ? R * rho[n] : R * rho[n] * y[n - 1];
    s *= std::norm(rho[n]);
    r.R[n] = R, r.s[n] = s;
  }
  return r;
}

double rel(long double got, long double want) { return static_cast<double>(std::abs(got - want) / std::abs(want)); }
double rel(LC got, LC want) { return static_cast<double>(std::abs(got - want) / std::abs(want)); }

}  // namespace

TEST_CASE("power-series ratios: the coefficients give y0(x) = 1/x - cot x", "[mie][ratio-series]") {
  // y₀(x) = ψ₁/ψ₀ = 1/x − cot x in closed form (ψ₁ = x j₁(x) = sin x/x − cos x, A&S 10.1.11);
  // evaluated in long double away from the cancellation of 1/x − cot x.
  for (double x : {0.3, 0.7, 1.0, 1.5}) {
    const long double xl = x;
    const long double want = 1.0L / xl - std::cos(xl) / std::sin(xl);
    std::vector<double> y(3), s(3);
    std::vector<StoredComplex<double>> rho(4), w(3), R(3);
    INFO("x = " << x);
    REQUIRE(series_ratios(x, C(1.05, 0.0), 1, Slot::value, std::sin(x), std::cos(x),
                          SeriesTables{y.data(), rho.data(), w.data(), nullptr, R.data(), s.data()}));
    CHECK(rel(y[0], want) <= 4 * std::numeric_limits<double>::epsilon());
  }
}

TEST_CASE("power-series ratios agree with the extended-precision recurrences", "[mie][ratio-series]") {
  const double eps = std::numeric_limits<double>::epsilon();
  const std::vector<double> xs = {1e-8, 1e-5, 3.7e-3, 0.05, 0.1, 0.37, 0.7071, 1.0, 1.2, 1.5};
  const std::vector<C> ms = {C(1.0 + 1e-10, 0), C(1.0001, 0), C(1.33, 1e-8), C(1.5, 0.1), C(0.75, 0),
                             C(1.0, 1e-5),      C(2.0, 1.0),  C(10, 10),    C(0, std::sqrt(2.0)), C(0, 0.5)};
  double worst = 0;
  int cases = 0;
  for (double x : xs)
    for (const C& m : ms) {
      if (!in_series_domain(x, m)) continue;
      const Slot slot = std::norm(m - 1.0) < 0.25 ? Slot::difference : Slot::value;
      const double cbrt_x = bound_cbrt(x);
      for (std::size_t N : {first_terms<double>(x, cbrt_x), max_terms<double>(x, cbrt_x)}) {
        std::vector<double> y(N + 1), s(N + 1);
        std::vector<StoredComplex<double>> rho(N + 2), w(N + 1), R(N + 1);
        std::vector<unsigned char> is_value(N + 1);
        if (!series_ratios(x, m, N, slot, std::sin(x), std::cos(x),
                           SeriesTables{y.data(), rho.data(), w.data(), is_value.data(), R.data(), s.data()}))
          continue;  // the caller falls back to the recurrences (tested by the referee grid)
        const Reference ref = extended_reference(x, m, N, slot);
        ++cases;
        INFO("x = " << x << ", m = " << m << ", N = " << N);
        // The Miller/Lentz start leaves the top entries of the reference's δ
        // within ε|y_N| of their value (log_derivative.hpp), so δ is compared
        // where its own size exceeds that: below N − 2.
        for (std::size_t n = 0; n <= N; ++n) {
          double e = rel(y[n], ref.y[n]);
          e = std::max(e, rel(LC(rho[n + 1].re, rho[n + 1].im), ref.rho[n + 1]));
          if (n >= 1) e = std::max({e, rel(LC(R[n].re, R[n].im), ref.R[n]), rel(s[n], ref.s[n])});
          if (n + 2 < N) e = std::max(e, rel(LC(w[n].re, w[n].im), ref.w[n]));
          INFO("n = " << n);
          // Worst case of the series: truncation ε/16, Horner's rounding
          // (2K + 4)ε (1+q)²/(1−q)² with K <= 34, q <= 0.26 (~200ε), a few ε
          // of the products; the products in the reference add nε.
          CHECK(e <= 256 * eps);
          worst = std::max(worst, e);
        }
      }
    }
  CHECK(cases > 40);
  std::cout << "[ratio series] " << cases << " tables, largest relative difference from the extended-precision "
            << "recurrences " << worst << " (" << worst / eps << " ulp)\n";
}
