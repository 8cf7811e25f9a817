// Start values of the downward recurrences (attenuvis/mie/detail/log_derivative.hpp): where
// miller_depth() allows it, the double core starts yₙ(x), yₙ(mx) and
// δₙ = yₙ(mx) − yₙ(x) from zeros K orders above the table instead of from
// Lentz's continued fraction.  Checked here against the independent start:
// Lentz's continued fraction evaluated in x87 extended precision.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "attenuvis/mie/detail/log_derivative.hpp"
#include "attenuvis/mie/detail/term_count.hpp"

namespace {

using namespace attenuvis::mie::detail;
using C = std::complex<double>;
using LC = std::complex<long double>;

struct StartValues {
  long double yx;
  LC yz;
};

// y_N(x) and y_N(mx) from Lentz in long double (the reference).
StartValues lentz_reference(double x, C m, std::size_t N) {
  const ScaledInverse<long double> over_x(x);
  const ScaledInverseComplex<long double, LC> over_z(x, LC(m.real(), m.imag()));
  StartValues v;
  v.yx = 1.0L / riccati_psi_ratio<long double, long double>(N + 1, over_x);
  v.yz = recip(riccati_psi_ratio<LC, long double>(N + 1, over_z));
  return v;
}

}  // namespace

TEST_CASE("Miller start of the downward recurrences agrees with Lentz's continued fraction",
          "[mie][start-values]") {
  const double eps = std::numeric_limits<double>::epsilon();
  const std::vector<double> xs = {1e-8, 1e-3, 0.1, 0.7, 1.0, 4.493409457909064, 6.283185307179585, 10.0, 30.0};
  const std::vector<C> ms = {{1.000001, 0}, {1.0001, 0}, {1.33, 1e-8}, {1.5, 0.1}, {2, 1}, {0, 0.6}, {10, 10}};
  int checked = 0;
  for (double x : xs) {
    for (C m : ms) {
      const std::size_t first = first_terms<double>(x, std::cbrt(x));
      for (std::size_t N : {first, first + 7, max_terms<double>(x, std::cbrt(x))}) {
        const std::size_t K = miller_depth(x, m, N);
        if (K == 0) continue;
        INFO("x = " << x << ", m = " << m << ", N = " << N << ", K = " << K);
        const StartValues ref = lentz_reference(x, m, N);
        const ScaledInverse<double> over_x(x);
        const ScaledInverseComplex<double, C> over_z(x, m);
        std::vector<double> y;
        std::vector<StoredComplex<double>> rho, w;
        std::vector<unsigned char> is_value;
        // Slot::value: w holds yₙ(mx).
        downward_ratios<double, C>(over_x, over_z, m, N, Slot::value, y, rho, w, is_value, K);
        CHECK(std::abs(y[N] - ref.yx) <= 4 * eps * std::abs(ref.yx));
        const LC yz(w[N].re, w[N].im);
        CHECK(std::abs(yz - ref.yz) <= 4 * eps * std::abs(ref.yz));
        // Slot::difference (the core uses it for |m − 1| < 0.5): w holds δₙ
        // (unless flagged a value), to within the ε·max(|y_N(x)|, |y_N(mx)|)
        // that the Lentz start (δ = yz − yx) itself carries.
        downward_ratios<double, C>(over_x, over_z, m, N, Slot::difference, y, rho, w, is_value, K);
        if (!is_value[N]) {
          const LC delta(w[N].re, w[N].im);
          const long double scale = std::max(std::abs(ref.yx), std::abs(ref.yz));
          CHECK(std::abs(delta - (ref.yz - ref.yx)) <= 4 * eps * scale);
        }
        ++checked;
      }
    }
  }
  // The Miller start is used for most of these small spheres (a <= N/2).
  CHECK(checked >= 100);
}

TEST_CASE("Miller start: not used where max(x, |mx|) exceeds half the table", "[mie][start-values]") {
  CHECK(miller_depth(10.0, C(10, 10), 39) == 0);  // |mx| = 141 > N
  CHECK(miller_depth(30.0, C(1.33, 0), 60) == 0);  // |mx| = 39.9 > 30
  CHECK(miller_depth(0.1, C(1.33, 0), 11) > 0);
}
