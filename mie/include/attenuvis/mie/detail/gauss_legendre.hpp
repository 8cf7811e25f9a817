// Gauss–Legendre quadrature of run-time order, with the nodes held as angles.
//
// Template detail of the Legendre-moment code (legendre_moments_impl.hpp); it is
// instantiated for double, for long double (by the tests) and for the 50-digit
// referee type.
//
// Why not μ = cos θ: the rule integrates the phase function of a large sphere,
// whose forward peak is only Δμ ≈ 1/x² wide.  A node μ stored in double is off by
// up to 1.1e-16 in absolute terms, i.e. by 1e-10 of the peak width at x = 1e3
// (1e-8 at x = 1e4), and the integral inherits that relative error.  Here each
// node is held as s = (1 − μ)/2 = sin²(θ/2) for the half μ >= 0 (the other half is
// its mirror μ → −μ), which keeps its full relative accuracy as θ → 0.
//
// Boost.Math provides Gauss–Legendre rules only at compile-time orders
// (boost::math::quadrature::gauss<Real, N>) and legendre_p_zeros(n) returns μ,
// which is exactly the representation avoided here; so the nodes are found by
// Newton's method in θ on Pₙ(cos θ):
//   θ ← θ − Pₙ sin θ / (n (μ Pₙ − Pₙ₋₁))        (dPₙ/dθ = n(μPₙ − Pₙ₋₁)/sin θ)
// from Tricomi's guess θₖ ≈ φₖ + cot φₖ/(8n²), φₖ = π(4k − 1)/(4n + 2) (A&S 22.16.6
// to second order; Newton converges from it in ~3 steps), eight nodes at a time so
// that the O(n) evaluations of independent nodes overlap.  For a wider Real (the
// referee) the nodes start from the double rule.
//
// Evaluation of Pₙ near μ = 1: Bonnet's recurrence (k+1)Pₖ₊₁ = (2k+1)μPₖ − kPₖ₋₁
// adds rounding that grows like n·ε there (7e-13 at n = 2001: 6e-13 relative in
// the first node θ₁ ≈ 2.4/n, 6e-9 in its weight), so for s <= ¼ it runs on the
// differences Dₖ = Pₖ − Pₖ₋₁ (Reinsch's modification):
//     Dₖ₊₁ = (k Dₖ − 2s (2k+1) Pₖ) / (k+1),   Pₖ₊₁ = Pₖ + Dₖ₊₁,
// obtained by subtracting (k+1)Pₖ from both sides.
//
// Weights: w = 2/(dPₙ/dθ)² (A&S 25.4.29 written in θ) at the computed node.  At an
// exact node this equals 2 sin²θ/(n Pₙ₋₁)², but the latter changes by n·δθ/|Pₙ₋₁|
// relative under a node error δθ (1e-12 at the first node of order 2001, where
// Pₙ₋₁ ~ 1e-3), whereas dPₙ/dθ is stationary up to cot θ·δθ (Legendre's equation
// gives d²Pₙ/dθ² = −cot θ dPₙ/dθ at a zero).  The weight pass runs in x87
// extended precision for double, so the recurrence's rounding stays out of it.
//
// Accuracy (tests/mie/test_legendre_moments.cpp, against the 50-digit rule): at
// order 2001 the nodes θ within 3e-16 relative and the weights within 7e-16 (order
// 4001: 8e-16 and 1.7e-15).
// Cost O(n²); a rule is built once per order and cached by the callers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <boost/math/constants/constants.hpp>

namespace attenuvis::mie::detail {

// The rule of order n restricted to μ >= 0: nodes with θ in (0, π/2].  For odd n
// the middle node μ = 0 (θ = π/2) is the last entry, with HALF its weight, so
// that Σ over the half of w·(f(μ) + f(−μ)) is the full rule's Σ w f.
template <class Real>
struct HalfGaussLegendre {
  std::size_t order = 0;
  std::vector<Real> s;  // sin²(θ/2) = (1 − μ)/2 of each node, ascending
  std::vector<Real> w;  // weights (the middle node's halved, see above)
};

inline constexpr std::size_t kNodeBlock = 8;

// Pₙ, Pₙ₋₁ and μPₙ − Pₙ₋₁ (= sin θ/n · dPₙ/dθ) at `count` <= kNodeBlock nodes
// s[j] = sin²(θⱼ/2), all on the same side of s = ¼ (`near`: s <= ¼).
template <class Real>
void legendre_block(std::size_t n, const Real* s, std::size_t count, bool near, Real* pn, Real* pn1,
                    Real* dn) {
  Real p[kNodeBlock], q[kNodeBlock], d[kNodeBlock], ts[kNodeBlock];
  for (std::size_t j = 0; j < kNodeBlock; ++j) {
    ts[j] = j < count ? 2 * s[j] : Real(0);
    q[j] = 1;          // P₀
    p[j] = 1 - ts[j];  // P₁
    d[j] = -ts[j];     // D₁
  }
  for (std::size_t k = 1; k < n; ++k) {
    const Real a = Real(2 * k + 1) / Real(k + 1), b = Real(k) / Real(k + 1);
    if (near) {
      for (std::size_t j = 0; j < kNodeBlock; ++j) {
        d[j] = b * d[j] - a * ts[j] * p[j];
        q[j] = p[j];
        p[j] += d[j];
      }
    } else {
      for (std::size_t j = 0; j < kNodeBlock; ++j) {
        const Real next = a * (p[j] - ts[j] * p[j]) - b * q[j];
        q[j] = p[j];
        p[j] = next;
      }
    }
  }
  for (std::size_t j = 0; j < count; ++j) {
    pn[j] = n == 0 ? Real(1) : p[j];
    pn1[j] = n == 0 ? Real(0) : q[j];
    // μPₙ − Pₙ₋₁ = Dₙ − 2sPₙ, without the cancellation of the plain form near μ = 1
    dn[j] = n == 0 ? Real(1) : (near ? d[j] - ts[j] * p[j] : (p[j] - ts[j] * p[j]) - q[j]);
  }
}

// Newton's method in θ for `count` nodes at once (theta in/out), then their weights.
template <class Real>
void newton_block(std::size_t n, Real* theta, std::size_t count, bool near, Real* s_out, Real* w_out) {
  using std::abs;
  using std::sin;
  const Real eps = std::numeric_limits<Real>::epsilon();
  const int max_steps = std::is_same_v<Real, double> ? 12 : 8;
  Real s[kNodeBlock]{}, pn[kNodeBlock]{}, pn1[kNodeBlock]{}, dn[kNodeBlock]{};
  for (int step = 0; step <= max_steps; ++step) {
    for (std::size_t j = 0; j < count; ++j) {
      const Real h = sin(theta[j] / 2);
      s[j] = h * h;
    }
    legendre_block(n, s, count, near, pn, pn1, dn);
    bool done = true;
    for (std::size_t j = 0; j < count; ++j) {
      const Real delta = pn[j] * sin(theta[j]) / (Real(n) * dn[j]);
      theta[j] -= delta;
      done = done && abs(delta) <= 4 * eps * theta[j];
    }
    if (done) break;
  }
  using Wide = std::conditional_t<std::is_same_v<Real, double>, long double, Real>;
  Wide ws[kNodeBlock]{}, wn[kNodeBlock]{}, wn1[kNodeBlock]{}, wd[kNodeBlock]{};
  for (std::size_t j = 0; j < count; ++j) {
    const Wide h = sin(Wide(theta[j]) / 2);
    ws[j] = h * h;
  }
  legendre_block<Wide>(n, ws, count, near, wn, wn1, wd);
  for (std::size_t j = 0; j < count; ++j) {
    const Wide sin2 = 4 * ws[j] * (1 - ws[j]);
    w_out[j] = Real(2 * sin2 / (Wide(n) * Wide(n) * wd[j] * wd[j]));
    const Real h = sin(theta[j] / 2);
    s_out[j] = h * h;
  }
}

template <class Real>
HalfGaussLegendre<Real> half_gauss_legendre(std::size_t n) {
  if (n == 0) throw std::invalid_argument("Gauss-Legendre rule: order must be >= 1");
  using std::cos;
  using std::sin;
  HalfGaussLegendre<Real> rule;
  rule.order = n;
  const std::size_t half = n / 2;
  rule.s.resize(half + (n % 2));
  rule.w.resize(half + (n % 2));
  std::vector<Real> theta(half);
  if constexpr (std::is_same_v<Real, double>) {
    const double pi = boost::math::constants::pi<double>(), nn = double(n);
    for (std::size_t k = 1; k <= half; ++k) {
      const double phi = pi * double(4 * k - 1) / (4 * nn + 2);
      theta[k - 1] = phi + cos(phi) / (sin(phi) * 8 * nn * nn);
    }
  } else {
    // Double nodes first: Newton in Real then needs ~2 steps instead of ~6.
    const HalfGaussLegendre<double> d = half_gauss_legendre<double>(n);
    for (std::size_t k = 0; k < half; ++k) theta[k] = 2 * std::asin(std::sqrt(d.s[k]));
  }
  // θ < π/3 is s < ¼: the nodes are ascending, so each block is on one side.
  const double third = boost::math::constants::pi<double>() / 3;
  for (std::size_t k0 = 0; k0 < half;) {
    const bool near = double(theta[k0]) < third;
    std::size_t count = 0;
    while (count < kNodeBlock && k0 + count < half && (double(theta[k0 + count]) < third) == near) ++count;
    newton_block<Real>(n, theta.data() + k0, count, near, rule.s.data() + k0, rule.w.data() + k0);
    k0 += count;
  }
  if (n % 2) {
    // μ = 0 is a node of every odd order: w = 2/(n Pₙ₋₁(0))², halved (see above).
    using Wide = std::conditional_t<std::is_same_v<Real, double>, long double, Real>;
    const Wide s_mid = Wide(0.5);
    Wide pn, pn1, dn;
    legendre_block<Wide>(n, &s_mid, 1, false, &pn, &pn1, &dn);
    rule.s[half] = Real(0.5);
    rule.w[half] = Real(1 / (Wide(n) * Wide(n) * pn1 * pn1));
  }
  return rule;
}

}  // namespace attenuvis::mie::detail
