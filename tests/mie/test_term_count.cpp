// The table lengths of the converged rule (attenuvis/mie/detail/term_count.hpp):
// the small-x bound, looked up from precomputed thresholds, against its own
// closed form ⌊3 + L/(2 ln(2/x))⌋ + 1 evaluated with a logarithm, and the
// cube root of the Airy bound against std::cbrt.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "attenuvis/mie/referee.hpp"
#include "attenuvis/mie/detail/term_count.hpp"

using namespace attenuvis::mie::detail;

namespace {

// The closed form, the floor capped at 64 (reached only by the referee's
// larger L near x = 1); `near` is set when 3 + L/(2 ln(2/x)) lies within 1e-9
// of an integer, where the rounding of the logarithm may move the floor by one.
template <class Real>
std::size_t small_x_terms_by_log(double x, bool& near) {
  const double v = 3.0 + tail_log_tolerance<Real>() / (2.0 * std::log(2.0 / x));
  near = std::abs(v - std::round(v)) < 1e-9 * v;
  return static_cast<std::size_t>(std::min(std::floor(v), 64.0)) + 1;
}

}  // namespace

// Double and long double fit every slice of the lookup table with two
// compares; the 50-digit referee (a larger L) does not, and takes the search
// that steps on from there.
TEMPLATE_TEST_CASE("term count: the small-x bound equals its closed form", "[mie][term-count]", double,
                   long double, attenuvis::mie::Referee) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> log10_x(-12.0, 0.0), linear_x(0.0, 1.0);
  int compared = 0, skipped = 0;
  for (int i = 0; i < 400000; ++i) {
    const double x = (i % 2) ? std::pow(10.0, log10_x(rng)) : linear_x(rng);
    if (!(x > 0 && x < 1)) continue;
    bool near = false;
    const std::size_t expected = small_x_terms_by_log<TestType>(x, near);
    if (near) {
      ++skipped;
      continue;
    }
    INFO("x = " << x);
    REQUIRE(small_x_terms<TestType>(x) == expected);
    ++compared;
  }
  CHECK(compared > 399000);
  CHECK(skipped < 100);
  // Next to every step of the floor below x = 1 up to the cap: one order
  // below just under the threshold, the higher one at it (t_j = 2 exp(−L/(2(j − 3)))).
  const double L = tail_log_tolerance<TestType>();
  for (int j = 4; j <= 64 && 2.0 * std::exp(-L / (2.0 * (j - 3))) < 1.0; ++j) {
    const double t = 2.0 * std::exp(-L / (2.0 * (j - 3)));
    INFO("j = " << j << ", t_j = " << t);
    CHECK(small_x_terms<TestType>(std::nextafter(t, 0.0)) == static_cast<std::size_t>(j));
    CHECK(small_x_terms<TestType>(t) == static_cast<std::size_t>(j + 1));
  }
}

TEST_CASE("term count: the Airy bound's cube root is within 4 ulps of std::cbrt", "[mie][term-count]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> log10_x(-8.0, 7.5);
  for (int i = 0; i < 200000; ++i) {
    const double x = std::pow(10.0, log10_x(rng));
    const double ref = std::cbrt(x);
    INFO("x = " << x);
    REQUIRE(std::abs(bound_cbrt(x) - ref) <= 4 * std::numeric_limits<double>::epsilon() * ref);
  }
}
