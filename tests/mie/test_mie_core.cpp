// Core behaviour of attenuvis::mie: API contract, the conventions documented
// in attenuvis/mie.hpp, and analytic limits.  Reference values are either
// closed-form limits (source cited at each test) or identities of the theory
// (B&H = Bohren & Huffman 1983, "Absorption and Scattering of Light by Small
// Particles", ch. 4–5); the double-vs-50-digit comparisons that protect each
// numerical trap are in test_mie_traps.cpp, published tables in
// test_mie_published.cpp and the stress grid in test_mie_referee.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>

#include "attenuvis/mie.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

double rel(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

bool finite(const mie::Efficiencies<double>& q) {
  return std::isfinite(q.qext) && std::isfinite(q.qsca) && std::isfinite(q.qabs) && std::isfinite(q.qback) &&
         std::isfinite(q.qpr) && std::isfinite(q.g);
}

}  // namespace

TEST_CASE("sphere(): Qext = Qsca + Qabs, Qpr = Qext - g Qsca, real m does not absorb", "[mie][core]") {
  for (double x : {1e-3, 0.7, 5.0, 60.0, 700.0})
    for (cd m : {cd(1.33, 0), cd(1.5, 0.1), cd(0.75, 0), cd(10, 10), cd(1.0001, 1e-8)}) {
      const auto q = mie::sphere(x, m);
      INFO("x=" << x << " m=" << m);
      REQUIRE(finite(q));
      CHECK(std::abs(q.qext - (q.qsca + q.qabs)) <= 1e-15 * q.qext);
      CHECK(std::abs(q.qpr - (q.qext - q.g * q.qsca)) <= 2e-16 * q.qext);
      CHECK(q.qsca > 0);
      CHECK(q.qabs >= 0);
      if (m.imag() == 0) CHECK(q.qabs == 0);
      CHECK(q.g > -1);
      CHECK(q.g < 1);
    }
}

TEST_CASE("amplitudes follow B&H: Qext = 4 Re S1(0)/x^2, Qback = 4|S1(180)|^2/x^2, S2(180) = -S1(180)",
          "[mie][core]") {
  // B&H eq. 4.76 (optical theorem), 4.82 (Qback) and the symmetry of πₙ, τₙ at
  // θ = 0 and π (B&H 4.48): S1(0) = S2(0), S1(π) = −S2(π).
  mie::Extras extras;
  extras.angles_deg = {0.0, 180.0};
  for (double x : {0.3, 4.0, 77.0})
    for (cd m : {cd(1.33, 1e-8), cd(1.5, 0.1), cd(2, 1)}) {
      const auto s = mie::scatter(x, m, extras);
      INFO("x=" << x << " m=" << m);
      CHECK(rel(4 * s.s1[0].real() / (x * x), s.q.qext) < 1e-13);
      CHECK(std::abs(s.s1[0] - s.s2[0]) <= 1e-14 * std::abs(s.s1[0]));
      CHECK(rel(4 * std::norm(s.s1[1]) / (x * x), s.q.qback) < 1e-12);
      CHECK(std::abs(s.s1[1] + s.s2[1]) <= 1e-13 * std::abs(s.s1[1]));
    }
}

TEST_CASE("Qsca and g Qsca equal the angular integrals of |S1|^2 + |S2|^2", "[mie][core]") {
  // Qsca = (1/x²)∫(|S1|²+|S2|²) dcosθ and g Qsca = (1/x²)∫cosθ(|S1|²+|S2|²) dcosθ
  // (B&H §3.4 and §4.5: the scattering cross section from the amplitude matrix for
  // unpolarised light; |S1|², |S2|² are the two polarised phase functions); integrated
  // here with 40-point Gauss–Legendre in cosθ, exact to ~1e-15 for x = 2
  // (the integrand is a polynomial of degree 2N ≈ 24 in cosθ).
  const double x = 2.0;
  const cd m(1.5, 0.02);
  boost::math::quadrature::gauss<double, 40> rule;
  mie::Extras extras;
  std::vector<double> weights;
  std::vector<double> mus;
  for (std::size_t i = 0; i < rule.abscissa().size(); ++i) {
    const double t = rule.abscissa()[i];
    for (double mu : {t, -t}) {
      if (t == 0 && mu < 0) continue;
      mus.push_back(mu);
      weights.push_back(rule.weights()[i]);
      extras.angles_deg.push_back(std::acos(mu) * 180.0 / M_PI);
    }
  }
  const auto s = mie::scatter(x, m, extras);
  double sca = 0, gsca = 0;
  for (std::size_t j = 0; j < mus.size(); ++j) {
    const double i = std::norm(s.s1[j]) + std::norm(s.s2[j]);
    sca += weights[j] * i;
    gsca += weights[j] * mus[j] * i;
  }
  CHECK(rel(sca / (x * x), s.q.qsca) < 1e-13);
  CHECK(rel(gsca / (x * x), s.q.g * s.q.qsca) < 1e-12);
}

TEST_CASE("Rayleigh limit at x = 1e-7 (B&H §5.1-5.2)", "[mie][core]") {
  // Qsca = (8/3) x⁴ |(m²−1)/(m²+2)|², Qabs = 4x Im[(m²−1)/(m²+2)], with relative
  // corrections O(x²|m|²) <= 1e-12 here; a₁ = −(2i/3) x³ (m²−1)/(m²+2) + O(x⁵) (B&H §5.1, the
  // small-x expansion of the Mie coefficients).
  const double x = 1e-7;
  for (cd m : {cd(1.5, 0.0), cd(1.33, 1e-3), cd(2, 1), cd(10, 10), cd(1 + 1e-6, 0), cd(0.75, 0)}) {
    const cd one(1.0);
    const cd alpha = (m - one) * (m + one) / (m * m + 2.0);  // (m−1)(m+1): exact for m near 1
    mie::Extras extras;
    extras.coefficients = true;
    const auto s = mie::scatter(x, m, extras);
    INFO("m=" << m);
    CHECK(rel(s.q.qsca, 8.0 / 3.0 * std::pow(x, 4) * std::norm(alpha)) < 1e-10);
    if (m.imag() > 0) CHECK(rel(s.q.qabs, 4 * x * alpha.imag()) < 1e-10);
    CHECK(s.q.qext > 0);
    const cd a1 = cd(0, -2.0 / 3.0) * std::pow(x, 3) * alpha;
    CHECK(std::abs(s.a[0] - a1) <= 1e-10 * std::abs(a1));
  }
}

TEST_CASE("perfectly conducting sphere: no absorption, small-x limit Qsca = (10/3) x^4", "[mie][core]") {
  // Small perfectly conducting sphere: σ = (10π/3) k⁴a⁶ (Jackson, Classical
  // Electrodynamics, 3rd ed., §10.1.C), i.e. Qsca = (10/3) x⁴, corrections O(x²).
  const auto small = mie::sphere(1e-4, mie::PerfectConductor{});
  CHECK(small.qabs == 0);
  CHECK(rel(small.qsca, 10.0 / 3.0 * 1e-16) < 1e-6);
  // A metal with huge |m| approaches it; the differences fall like 1/|m|
  // (measured: 1.6e-3, 1.6e-5, 1.6e-7 in Qext at x = 0.5 for |m| = 1.4e2, 1.4e4,
  // 1.4e6), so |m| = 1.4e6 must agree to 1e-4.
  for (double x : {0.5, 20.0, 300.0}) {
    const auto pec = mie::sphere(x, mie::PerfectConductor{});
    const auto metal = mie::sphere(x, cd(1e6, 1e6));
    INFO("x=" << x);
    REQUIRE(finite(pec));
    CHECK(pec.qext == Approx(pec.qsca).epsilon(1e-15));
    CHECK(rel(metal.qsca, pec.qsca) < 1e-4);
    CHECK(rel(metal.qext, pec.qext) < 1e-4);
  }
}

TEST_CASE("term rules: converged goes beyond Wiscombe's N, wiscombe uses exactly N", "[mie][core]") {
  for (double x : {0.01, 1.0, 10.0, 1000.0}) {
    const std::size_t nw = mie::wiscombe_terms(x);
    CHECK(nw == static_cast<std::size_t>(x + 4.05 * std::cbrt(x) + 2.0));
    mie::Options w;
    w.terms = mie::TermRule::wiscombe;
    CHECK(mie::sphere(x, cd(1.5, 0.1), w).terms == nw);
    if (x >= 1) CHECK(mie::sphere(x, cd(1.5, 0.1)).terms > nw);
  }
}

TEST_CASE("working precisions agree where double is accurate", "[mie][core]") {
  mie::Options d, e;
  d.precision = mie::Precision::double_precision;
  e.precision = mie::Precision::extended;
  for (double x : {0.1, 30.0, 90.0}) {
    const auto qd = mie::sphere(x, cd(1.33, 1e-5), d);
    const auto qe = mie::sphere(x, cd(1.33, 1e-5), e);
    CHECK(rel(qd.qext, qe.qext) < 1e-12);
    CHECK(rel(qd.qback, qe.qback) < 1e-11);
  }
}

TEST_CASE("coefficients: n-th entry is aₙ, count equals terms", "[mie][core]") {
  mie::Extras extras;
  extras.coefficients = true;
  const auto s = mie::scatter(3.0, cd(1.5, 0.0), extras);
  REQUIRE(s.a.size() == s.q.terms);
  REQUIRE(s.b.size() == s.q.terms);
  // Non-absorbing: aₙ = U/(U − iV) with U, V real (B&H §4.4, aₙ written with ψ and
  // χ), so Re aₙ = |aₙ|² exactly: each partial wave lies on the unitarity circle.
  for (std::size_t n = 0; n < 5; ++n) {
    CHECK(std::abs(s.a[n].real() - std::norm(s.a[n])) <= 1e-15);
    CHECK(std::abs(s.b[n].real() - std::norm(s.b[n])) <= 1e-15);
  }
}

TEST_CASE("bad input is rejected with a message naming it", "[mie][core]") {
  CHECK_THROWS_WITH(mie::sphere(0.0, cd(1.5, 0)), Catch::Contains("size parameter"));
  CHECK_THROWS_AS(mie::sphere(-1.0, cd(1.5, 0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(NAN, cd(1.5, 0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(INFINITY, cd(1.5, 0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(3e7, cd(1.5, 0)), std::invalid_argument);
  CHECK_THROWS_WITH(mie::sphere(1.0, cd(1.5, -0.1)), Catch::Contains("refractive index"));
  CHECK_THROWS_AS(mie::sphere(1.0, cd(NAN, 0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(1.0, cd(0, 0)), std::invalid_argument);
}

TEST_CASE("domain: inputs outside it are rejected with the value and the range", "[mie][domain]") {
  // The fuzzer's regression lines (fuzz/regressions/mie_line/) gave NaN or
  // finite nonsense (Qback 6.27e6 at x = 1e4, m = 1e154) before the domain
  // of attenuvis/mie.hpp was checked; each must now be a clean rejection.
  struct Bad {
    double x;
    cd m;
    const char* names;  // what the message must contain
  } bad[] = {{1, cd(1e172, 0), "1e+172"}, {1e-200, cd(1.5, 0.1), "1e-08"}, {1e4, cd(1e154, 0), "1e+154"},
             {1, cd(1e-300, 0), "|m| >= 0.5"}, {2e6, cd(1.33, 0), "1000000"}, {1, cd(1.5, 2e6), "k <= 1000000"}};
  for (const Bad& b : bad) {
    INFO("x = " << b.x << " m = " << b.m);
    try {
      mie::sphere(b.x, b.m);
      FAIL("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Catch::Contains(b.names));
    }
  }
  // The edges themselves are inside and finite.
  for (double x : {1e-8, 1e6})
    for (cd m : {cd(0.5, 0), cd(0, 0.5), cd(1e6, 0), cd(1e6, 1e6)}) {
      if (x == 1e6 && m == cd(1e6, 1e6)) continue;  // same path as (1e6, 0); ~1 s each at x = 1e6
      const auto q = mie::sphere(x, m);
      INFO("x = " << x << " m = " << m);
      CHECK(std::isfinite(q.qext));
      CHECK(std::isfinite(q.qback));
      CHECK(q.qext > 0);
    }
}
