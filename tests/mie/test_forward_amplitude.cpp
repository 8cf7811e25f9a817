// S(0) at complex size parameter (mie/forward_amplitude.hpp), the integrand of
// the contour extinction integral (weather/contour_extinction.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"

using attenuvis::mie::Precision;
using attenuvis::mie::forward_amplitude;

namespace {
// The rows of a reference table in tests/data/mie/: x, m and S(0).
struct ReferenceRow {
  std::complex<double> x, m, s0;
};
std::vector<ReferenceRow> reference_rows(const std::string& name) {
  std::ifstream in(std::string(ATTENUVIS_TEST_DATA_DIR) + "/mie/" + name);
  REQUIRE(in);
  std::vector<ReferenceRow> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 'x') continue;
    std::istringstream s(line);
    std::vector<double> v;
    for (std::string cell; std::getline(s, cell, ',');) v.push_back(std::stod(cell));
    REQUIRE(v.size() == 6);
    rows.push_back({{v[0], v[1]}, {v[2], v[3]}, {v[4], v[5]}});
  }
  return rows;
}
}  // namespace

TEST_CASE("forward amplitude at complex x: 60-digit mpmath table", "[mie][complex-x]") {
  // tests/data/mie/forward_amplitude_mpmath.csv: validation/scripts/forward_amplitude_reference.py,
  // mpmath at 60 digits from besselj/bessely (B&H eq. 4.53 form of a_n, b_n), an
  // implementation independent of ours (log-derivative ratios, long double).
  int rows = 0;
  double worst = 0, worst_double = 0;
  for (const auto& [x, m, ref] : reference_rows("forward_amplitude_mpmath.csv")) {
    for (Precision a : {Precision::extended, Precision::double_precision}) {
      const auto fa = forward_amplitude(x, m, a);
      const double err = std::abs(fa.s0 - ref);
      // The bound the contour integral charges for rounding (contour_extinction.cpp):
      const double bound = fa.rounding_bound();
      INFO("x = " << x << ", m = " << m << (a == Precision::extended ? " (long double)" : " (double)") << ": S(0) "
                  << fa.s0 << " vs " << ref << ", |error| " << err << ", rounding bound " << bound);
      CHECK(err <= bound);
      if (a == Precision::extended) {
        CHECK(err <= 1e-13 * std::abs(ref));
        worst = std::max(worst, err / std::abs(ref));
      } else {
        // The table reaches Im x = 4, the contour path's height: a 1e-9 size
        // integral needs S(0) to ~1e-11 there (contour_extinction.cpp).
        CHECK(err <= 1e-12 * std::abs(ref));
        worst_double = std::max(worst_double, err / std::abs(ref));
      }
    }
    ++rows;
  }
  CHECK(rows == 18);
  WARN("forward amplitude vs mpmath: max relative error " << worst << " (long double), " << worst_double
                                                            << " (double) over " << rows << " points");
}

TEST_CASE("forward amplitude up to its range, 3e5: 60-digit mpmath values", "[mie][complex-x]") {
  // tests/data/mie/forward_amplitude_mpmath_large.csv: the same script, psi_n
  // by Miller's algorithm (mpmath's besselj does not converge at these
  // orders).  Raindrops in the ultraviolet: water at 200 nm on the contour's
  // height and on the real axis, water at 550 nm.
  int rows = 0;
  double worst[2] = {0, 0};  // double, long double
  for (const auto& [x, m, ref] : reference_rows("forward_amplitude_mpmath_large.csv")) {
    for (Precision a : {Precision::extended, Precision::double_precision}) {
      const auto fa = forward_amplitude(x, m, a);
      const double err = std::abs(fa.s0 - ref);
      INFO("x = " << x << ", m = " << m << (a == Precision::extended ? " (long double)" : " (double)") << ": S(0) "
                  << fa.s0 << " vs " << ref << ", |error| " << err << ", rounding bound " << fa.rounding_bound());
      // The bound the contour integral charges for rounding; in long double
      // also ~ terms x its unit roundoff (2.8e5 x 1.1e-19 = 3e-14).  In
      // double the error reached 4.3e-11 of |S(0)| at x = 2e5 + 4i, a
      // hundredth of the bound charged.
      CHECK(err <= fa.rounding_bound());
      if (a == Precision::extended) CHECK(err <= 1e-13 * std::abs(ref));
      worst[a == Precision::extended] = std::max(worst[a == Precision::extended], err / std::abs(ref));
    }
    ++rows;
  }
  CHECK(rows == 3);
  WARN("forward amplitude vs mpmath, |x| 1.5e5 ... 2.8e5: max relative error " << worst[1] << " (long double), "
                                                                                << worst[0] << " (double)");
  CHECK_THROWS_WITH(forward_amplitude({3.1e5, 4.0}, {1.33, 0.0}), Catch::Contains("|x| <= 3e5"));
}

TEST_CASE("forward amplitudes in batches agree with one-by-one calls", "[mie][complex-x]") {
  // forward_amplitudes runs up to sixteen series side by side on tables as long
  // as the largest |x| needs (eight where some |x| > 2e4); points spanning |x|
  // 0.5...25000 must give the single-call values within their rounding
  // bounds: the first eight (with 25000) in a batch of eight, the ninth alone
  // in a batch of sixteen (a short last batch).
  const std::vector<std::complex<double>> x{{0.5, 0.1},   {1500.0, 4.0}, {5.0, 1.0},     {80.0, 4.0}, {300.0, 0.0},
                                            {20.0, 2.0},  {700.0, 3.0},  {25000.0, 4.0}, {10.0, 0.5}};
  for (std::complex<double> m : {std::complex<double>(1.333, 1.96e-9), {1.5, 0.1}, {10.0, 10.0}})
    for (Precision a : {Precision::extended, Precision::double_precision}) {
      std::vector<attenuvis::mie::ForwardAmplitude> batch(x.size());
      attenuvis::mie::forward_amplitudes(x.data(), x.size(), m, a, batch.data());
      for (std::size_t k = 0; k < x.size(); ++k) {
        const auto one = forward_amplitude(x[k], m, a);
        INFO("x = " << x[k] << ", m = " << m << ": batch " << batch[k].s0 << ", single " << one.s0);
        CHECK(std::abs(batch[k].s0 - one.s0) <= batch[k].rounding_bound() + one.rounding_bound());
        CHECK(batch[k].terms == one.terms);
      }
    }
  // A bad point anywhere in the batch is rejected before any work.
  const std::vector<std::complex<double>> bad{{10.0, 1.0}, {10.0, -1.0}};
  std::vector<attenuvis::mie::ForwardAmplitude> out(bad.size());
  CHECK_THROWS_WITH(attenuvis::mie::forward_amplitudes(bad.data(), bad.size(), {1.33, 0.0}, Precision::double_precision,
                                                       out.data()),
                    Catch::Contains("0 <= Im x <= 20"));
}

TEST_CASE("forward amplitude on the real axis gives sphere()'s Q_ext", "[mie][complex-x]") {
  // Optical theorem, B&H eq. 4.76: Q_ext = 4 Re S(0) / x^2; sphere() is the
  // referee-checked product (tests/mie/test_mie_referee.cpp, 1e-10).
  double worst = 0;
  for (double x : {1e-3, 0.1, 1.0, 4.493409457909064, 30.0, 250.0, 1000.0, 3000.0})
    for (std::complex<double> m : {std::complex<double>(1.333, 1.96e-9), {1.5, 0.1}, {1.01, 0.0}, {10.0, 10.0}}) {
      const auto fa = forward_amplitude({x, 0.0}, m);
      const double q = attenuvis::mie::sphere(x, m).qext;
      const double rel = std::abs(4 * fa.s0.real() / (x * x) / q - 1);
      // For small non-absorbing spheres Re S(0) ~ x^6 sits under Im S(0) ~ x^3:
      // its relative accuracy is that of |S(0)|, which is what the contour
      // integral charges (the rounding bound), not that of Q_ext itself.
      const double bound = 4 / (x * x) * fa.rounding_bound();
      INFO("x = " << x << ", m = " << m << ": " << 4 * fa.s0.real() / (x * x) << " vs " << q << ", bound " << bound);
      CHECK(std::abs(4 * fa.s0.real() / (x * x) - q) <= 1e-11 * q + bound);
      worst = std::max(worst, rel);
    }
  WARN("forward amplitude vs sphere() on the real axis: max relative difference in Q_ext " << worst);
}

TEST_CASE("forward amplitude: bad arguments are rejected", "[mie][complex-x]") {
  CHECK_THROWS_WITH(forward_amplitude({10.0, -1.0}, {1.33, 0.0}), Catch::Contains("0 <= Im x <= 20"));
  CHECK_THROWS_AS(forward_amplitude({0.0, 1.0}, {1.33, 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(forward_amplitude({10.0, 1.0}, {1.0 + 1e-8, 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(forward_amplitude({10.0, 1.0}, {1.33, -0.1}), std::invalid_argument);
  CHECK_THROWS_AS(forward_amplitude({std::nan(""), 1.0}, {1.33, 0.0}), std::invalid_argument);
}
