// Scattering matrix S11, S12, S33, S34, the phase function and the lidar
// quantities of one sphere (attenuvis/mie/scattering_matrix.hpp).
//
// Reference values:
//  * Bohren & Huffman (1983) appendix A, p. 482 (tests/data/mie/
//    bohren_huffman_appendix_a.csv): S11/S11(0), −S12/S11, S33/S11, S34/S11 for
//    x = 2π·0.525/0.6328, m = 1.55, to half a unit in the last printed digit;
//    two entries (99°: S33/S11 printed −0.717397E-02 for −0.7173975E-02; 126°:
//    S34/S11 printed 0.795798E-01 for 0.7957986E-01) are single-precision
//    roundings of BHMIE and are allowed 2e-6 relative, as in test_mie_published.cpp;
//  * exact identities: S11² = S12² + S33² + S34² (pure Mueller matrix, B&H §3.3),
//    ∫ p dΩ = 4π (Gauss–Legendre of an order that integrates the polynomial
//    p(μ) of degree 2N exactly, Boost.Math), at θ = 180°: S12 = S34 = 0,
//    S33 = −S11 (S2(π) = −S1(π), B&H 4.75), Qback/(4π) = Qsca p(π)/(4π).
#include <catch2/catch.hpp>

#include "csv_rows.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

struct Printed {
  double value;
  double tol;  // half a unit in the last printed digit (0.dddddd E±ee)
};

Printed printed(const std::string& text) {
  const auto e = text.find_first_of("eE");
  return {std::stod(text), 0.5e-6 * std::pow(10.0, std::stoi(text.substr(e + 1)))};
}

using mie_test::read_csv_rows;

}  // namespace

TEST_CASE("Scattering matrix: Bohren & Huffman appendix A", "[mie][scattering_matrix][published]") {
  const auto rows = read_csv_rows("bohren_huffman_appendix_a.csv");
  REQUIRE(rows.size() == 21);
  std::vector<double> angles;
  for (const auto& r : rows) angles.push_back(std::stod(r[0]));
  const double x = 2.0 * boost::math::constants::pi<double>() * 0.525 / 0.6328;
  const mie::ScatteringMatrix sm = mie::scattering_matrix(x, cd(1.55, 0.0), angles);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double s11 = sm.s11[j];
    const double got[4] = {s11 / sm.s11[0], -sm.s12[j] / s11, sm.s33[j] / s11, sm.s34[j] / s11};
    for (int c = 0; c < 4; ++c) {
      const Printed p = printed(rows[j][c + 1]);
      double tol = p.tol;
      if ((rows[j][0] == "99" && c == 2) || (rows[j][0] == "126" && c == 3))
        tol = 2e-6 * std::abs(p.value);  // see header
      INFO("theta = " << rows[j][0] << ", column " << c + 1 << ": " << got[c] << " vs printed " << p.value);
      CHECK(std::abs(got[c] - p.value) <= tol);
    }
  }
}

TEST_CASE("Scattering matrix: pure Mueller identity and normalisation of p", "[mie][scattering_matrix]") {
  const double pi = boost::math::constants::pi<double>();
  for (const double x : {0.1, 1.0, 5.0, 20.0})
    for (const cd m : {cd(1.33, 1e-8), cd(1.5, 0.1), cd(10.0, 10.0)}) {
      INFO("x = " << x << ", m = " << m);
      // 60-point Gauss–Legendre integrates degree <= 119 exactly: N <= 59 terms.
      using rule = boost::math::quadrature::gauss<double, 60>;
      std::vector<double> angles;
      std::vector<double> weights;
      for (std::size_t k = 0; k < rule::abscissa().size(); ++k)
        for (const double sign : {1.0, -1.0}) {
          if (k == 0 && sign < 0 && rule::abscissa()[0] == 0.0) continue;
          angles.push_back(std::acos(sign * rule::abscissa()[k]) * 180.0 / pi);
          weights.push_back(rule::weights()[k]);
        }
      mie::Extras ex;
      ex.angles_deg = angles;
      const auto s = mie::scatter(x, m, ex);
      REQUIRE(s.q.terms <= 59);
      const auto sm = mie::scattering_matrix(x, s);
      double integral = 0;
      for (std::size_t j = 0; j < angles.size(); ++j) {
        integral += 2 * pi * weights[j] * sm.phase[j];
        const double lhs = sm.s11[j] * sm.s11[j];
        const double rhs = sm.s12[j] * sm.s12[j] + sm.s33[j] * sm.s33[j] + sm.s34[j] * sm.s34[j];
        CHECK(std::abs(lhs - rhs) <= 1e-13 * lhs);
      }
      CHECK(std::abs(integral - 4 * pi) <= 1e-12 * 4 * pi);
    }
}

TEST_CASE("Scattering matrix at 180 degrees and the lidar quantities", "[mie][scattering_matrix]") {
  const double pi = boost::math::constants::pi<double>();
  for (const double x : {0.1, 3.0, 50.0, 1000.0})
    for (const cd m : {cd(1.33, 1e-8), cd(1.5, 0.1), cd(10.0, 10.0)}) {
      INFO("x = " << x << ", m = " << m);
      const auto sm = mie::scattering_matrix(x, m, {180.0});
      const auto q = mie::sphere(x, m);
      CHECK(std::abs(sm.s12[0]) <= 1e-12 * sm.s11[0]);
      CHECK(std::abs(sm.s34[0]) <= 1e-12 * sm.s11[0]);
      CHECK(std::abs(sm.s33[0] + sm.s11[0]) <= 1e-12 * sm.s11[0]);
      const mie::Lidar l = mie::lidar(q);
      CHECK(l.backscatter_per_sr == q.qback / (4 * pi));
      CHECK(std::abs(l.backscatter_per_sr - q.qsca * sm.phase[0] / (4 * pi)) <= 1e-10 * l.backscatter_per_sr);
      CHECK(std::abs(l.lidar_ratio_sr - 4 * pi * q.qext / q.qback) <= 1e-15 * l.lidar_ratio_sr);
      CHECK(l.linear_depolarisation == 0.0);
    }
}

TEST_CASE("Scattering matrix: bad input", "[mie][scattering_matrix]") {
  mie::Extras ex;
  ex.coefficients = true;  // no angles: no amplitudes
  auto s = mie::scatter(1.0, cd(1.5, 0.0), ex);
  s.s1.clear();
  s.angles_deg = {10.0};
  CHECK_THROWS_AS(mie::scattering_matrix(1.0, s), std::invalid_argument);
  CHECK_THROWS_AS(mie::scattering_matrix(-1.0, cd(1.5, 0.0), {10.0}), std::invalid_argument);
}

// S1, S2 of scatter() against B&H 4.74 summed here, order by order in long
// double, from the coefficients aₙ, bₙ scatter() returns with them (πₙ, τₙ by
// B&H 4.47 from μ = cos θ in long double).  The series accumulates the
// amplitudes a block of orders at a time with the angles in vector lanes;
// this checks that every order is added once, to every angle, up to where
// the series stops (x = 50 and 700 run through several blocks; angle counts
// that fill no whole vector).  Bound: the rounding of double sums of up to
// ~730 terms, relative to the largest |S| (the forward peak).
TEST_CASE("Amplitudes S1, S2 equal B&H 4.74 summed from the returned coefficients", "[mie][scattering_matrix]") {
  const long double pi = boost::math::constants::pi<long double>();
  const std::vector<double> one = {37.5}, nine = {0, 10, 20, 45, 90, 120, 150, 170, 180};
  std::vector<double> fine;
  for (int k = 0; k <= 24; ++k) fine.push_back(7.5 * k);
  for (const double x : {0.1, 3.0, 50.0, 700.0}) {
    for (const cd m : {cd(1.33, 1e-8), cd(1.5, 0.1), cd(1.0001, 0.0)}) {
      for (const std::vector<double>* list_p : std::vector<const std::vector<double>*>{&one, &nine, &fine}) {
        const std::vector<double>& list = *list_p;
        mie::Extras ex;
        ex.coefficients = true;
        ex.angles_deg = std::vector<double>(list.begin(), list.end());
        const auto s = mie::scatter(x, m, ex);
        REQUIRE(s.a.size() == s.q.terms);
        REQUIRE(s.s1.size() == list.size());
        long double largest = 0;
        std::vector<std::complex<long double>> r1(list.size()), r2(list.size());
        for (std::size_t j = 0; j < list.size(); ++j) {
          const long double mu = std::cos(static_cast<long double>(list[j]) * pi / 180);
          long double p0 = 0, p1 = 1;  // π_{n-1}, πₙ
          for (std::size_t n = 1; n <= s.a.size(); ++n) {
            const long double rn = n;
            if (n >= 2) {
              const long double p2 = ((2 * rn - 1) * mu * p1 - rn * p0) / (rn - 1);
              p0 = p1;
              p1 = p2;
            }
            const long double tau = rn * mu * p1 - (rn + 1) * p0;
            const long double f = (2 * rn + 1) / (rn * (rn + 1));
            const std::complex<long double> a(s.a[n - 1].real(), s.a[n - 1].imag());
            const std::complex<long double> b(s.b[n - 1].real(), s.b[n - 1].imag());
            r1[j] += f * (a * p1 + b * tau);
            r2[j] += f * (a * tau + b * p1);
          }
          largest = std::max({largest, std::abs(r1[j]), std::abs(r2[j])});
        }
        for (std::size_t j = 0; j < list.size(); ++j) {
          INFO("x = " << x << ", m = " << m << ", theta = " << list[j] << " deg of " << list.size());
          const std::complex<long double> d1 = std::complex<long double>(s.s1[j].real(), s.s1[j].imag()) - r1[j];
          const std::complex<long double> d2 = std::complex<long double>(s.s2[j].real(), s.s2[j].imag()) - r2[j];
          CHECK(static_cast<double>(std::abs(d1) / largest) < 1e-13);
          CHECK(static_cast<double>(std::abs(d2) / largest) < 1e-13);
        }
      }
    }
  }
}

// The cosines of an angle list are kept per thread for the next sphere; a
// sphere at another list, or at the first one again, must not see stale ones.
TEST_CASE("Amplitudes do not depend on the angle list asked for before", "[mie][scattering_matrix]") {
  mie::Extras ea, eb;
  ea.angles_deg = {0, 30, 60, 90};
  eb.angles_deg = {5, 95, 175};
  const auto first_a = mie::scatter(20.0, cd(1.5, 0.01), ea);
  const auto then_b = mie::scatter(20.0, cd(1.5, 0.01), eb);
  const auto again_a = mie::scatter(20.0, cd(1.5, 0.01), ea);
  mie::Scattering<double> fresh_b;
  std::thread([&] { fresh_b = mie::scatter(20.0, cd(1.5, 0.01), eb); }).join();
  CHECK(then_b.s1 == fresh_b.s1);
  CHECK(then_b.s2 == fresh_b.s2);
  CHECK(again_a.s1 == first_a.s1);
  CHECK(again_a.s2 == first_a.s2);
}
