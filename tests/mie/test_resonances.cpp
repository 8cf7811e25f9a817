// The poles of a_n, b_n near the real axis (mie/resonances.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/resonances.hpp"

namespace mie = attenuvis::mie;
using Complex = std::complex<double>;

namespace {

// Water at 550 nm (Hale & Querry 1973).
const Complex kWater(1.333, 1.96e-9);

const mie::ResonanceBracket* find(const std::vector<mie::ResonanceBracket>& brackets, int order,
                                  mie::ResonanceMode mode, double x0) {
  for (const auto& b : brackets)
    if (b.order == order && b.mode == mode && b.x_lo <= x0 && x0 <= b.x_hi) return &b;
  return nullptr;
}

}  // namespace

TEST_CASE("resonance poles agree with an independent computation", "[mie][resonances]") {
  // Reference poles: Newton on the denominators of B&H 4.53 divided by psi_n(mx) xi_n(x), with
  // scipy.special's spherical_jn/spherical_yn at complex x (finite-difference derivative, step
  // 1e-7), started from the real zeros of the lossless function found on a 0.05 grid; m = 1.333 +
  // 1.96e-9i.  Positions to ~1e-13, half-widths to ~1e-13 absolute.
  struct Reference {
    int order;
    mie::ResonanceMode mode;
    double x0, half_width;
  };
  const Reference refs[] = {
      {30, mie::ResonanceMode::magnetic, 26.10429880661002, 2.3607352833e-02},
      {100, mie::ResonanceMode::electric, 90.58858544137441, 1.4001460476e-03},
      {100, mie::ResonanceMode::electric, 86.34488342571643, 1.5218702803e-05},
      {132, mie::ResonanceMode::electric, 116.08796511297520, 6.6792353265e-06},
      {138, mie::ResonanceMode::electric, 110.52427105551264, 1.5874629556e-07},
  };
  const auto brackets = mie::resonance_brackets(kWater.real(), 20, 120);
  for (const auto& ref : refs) {
    INFO("order " << ref.order << " at " << ref.x0);
    const auto* b = find(brackets, ref.order, ref.mode, ref.x0);
    REQUIRE(b != nullptr);
    const mie::Resonance r = mie::locate_resonance(*b, kWater);
    CHECK(std::abs(r.pole.real() - ref.x0) < 1e-10);
    CHECK(std::abs(r.half_width() - ref.half_width) < 1e-6 * ref.half_width + 1e-12);
  }
}

TEST_CASE("a located pole and its residue describe a_n near the resonance", "[mie][resonances]") {
  // a_n from the Mie series itself (mie::scatter, checked against the 50-digit referee) at two
  // points a half-width either side of x0: the difference is the pole term's difference, the
  // regular part changing by ~|h'| gamma only.
  const auto brackets = mie::resonance_brackets(kWater.real(), 85, 92);
  int checked = 0;
  for (const auto& b : brackets) {
    const mie::Resonance r = mie::locate_resonance(b, kWater);
    const double gamma = r.half_width();
    if (gamma < 1e-6 || gamma > 1e-2) continue;  // resolvable by the series at these points, and narrow
    mie::Extras extras;
    extras.coefficients = true;
    const double x1 = r.pole.real() - gamma, x2 = r.pole.real() + gamma;
    const auto s1 = mie::scatter(x1, kWater, extras), s2 = mie::scatter(x2, kWater, extras);
    const auto& c1 = b.mode == mie::ResonanceMode::electric ? s1.a : s1.b;
    const auto& c2 = b.mode == mie::ResonanceMode::electric ? s2.a : s2.b;
    const Complex series = c1[b.order - 1] - c2[b.order - 1];
    const Complex pole = r.residue / (x1 - r.pole) - r.residue / (x2 - r.pole);
    INFO("order " << b.order << " pole " << r.pole << " residue " << r.residue);
    CHECK(std::abs(series - pole) < 1e-3 * std::abs(pole));
    // A passive sphere's |a_n| <= 1, so the peak |R|/gamma of the pole term is at most ~1.
    CHECK(std::abs(r.residue) <= 1.01 * gamma);
    ++checked;
  }
  CHECK(checked >= 5);
}

TEST_CASE("the width estimate of a bracket is not below the located residue", "[mie][resonances]") {
  // resonance_plan.hpp charges brackets it does not locate with their width estimate.
  for (const Complex m : {kWater, Complex(1.3109, 1.35e-4)}) {
    const auto brackets = mie::resonance_brackets(m.real(), 1, 150);
    std::size_t located = 0;
    for (const auto& b : brackets) {
      if (b.width_estimate < 1e-14) continue;  // below any bound that matters; deep modes need not converge
      const mie::Resonance r = mie::locate_resonance(b, m);
      INFO("order " << b.order << " pole " << r.pole << " |R| " << std::abs(r.residue) << " estimate "
                    << b.width_estimate);
      CHECK(std::abs(r.residue) <= b.width_estimate);
      ++located;
    }
    CHECK(located > 500);
  }
}

TEST_CASE("resonance brackets refuse arguments outside their range", "[mie][resonances]") {
  CHECK_THROWS_AS(mie::resonance_brackets(1.0, 1, 10), std::invalid_argument);
  CHECK_THROWS_AS(mie::resonance_brackets(1.33, 0, 10), std::invalid_argument);
  CHECK_THROWS_AS(mie::resonance_brackets(1.33, 10, 1), std::invalid_argument);
  CHECK_THROWS_AS(mie::resonance_brackets(1.33, 1, 2e5), std::invalid_argument);
  const auto brackets = mie::resonance_brackets(1.33, 20, 30);
  REQUIRE_FALSE(brackets.empty());
  CHECK_THROWS_AS(mie::locate_resonance(brackets.front(), Complex(1.33, 0.5)), std::invalid_argument);
}
