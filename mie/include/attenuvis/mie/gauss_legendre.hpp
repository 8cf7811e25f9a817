// Gauss–Legendre quadrature of run-time order, with the nodes held as angles.
//
// Template detail of the Legendre-moment code (legendre_moments_impl.hpp); it is
// instantiated for double and for the 50-digit referee type.
//
// Why not μ = cos θ: the rule integrates the phase function of a large sphere,
// whose forward peak is only Δμ ≈ 1/x² wide.  A node μ stored in double is off by
// up to 1.1e-16 in absolute terms, i.e. by 1e-10 of the peak width at x = 1e3
// (1e-8 at x = 1e4), and the integral inherits that relative error.  Here each
// node is held as s = (1 − μ)/2 = sin²(θ/2) for the half μ >= 0 (the other half is
// its mirror μ → −μ), which keeps its full relative accuracy as θ → 0; every
// recurrence that uses the node takes μ·v as v − 2s·v.
//
// Boost.Math provides Gauss–Legendre rules only at compile-time orders
// (boost::math::quadrature::gauss<Real, N>) and legendre_p_zeros(n) returns μ,
// which is exactly the representation avoided here; so the nodes are found by
// Newton's method in θ on Pₙ(cos θ):
//   θ ← θ − Pₙ sin θ / (n (μ Pₙ − Pₙ₋₁))        (dPₙ/dθ = n(μPₙ − Pₙ₋₁)/sin θ)
// from Tricomi's first guess θₖ = π(4k − 1)/(4n + 2) (the guess of Numerical
// Recipes' gauleg; Newton converges from it for every k and n), and the weights
// are wₖ = 2 sin²θₖ / (n Pₙ₋₁(μₖ))²  (Abramowitz & Stegun 25.4.29).  Pₙ and Pₙ₋₁
// come from the three-term recurrence (Bonnet) in the s-form, O(n) per
// evaluation, O(n²) per rule: a rule is built once per order and cached by the
// callers (legendre_moments_impl.hpp).  For a wider Real (the referee) the nodes
// start from the double rule and Newton runs until the correction is below the
// Real's ε, typically two steps.
//
// Accuracy (measured in tests/mie/test_legendre_moments.cpp against the 50-digit
// rule): nodes θ within a few ulps relative, Σw = 2 to ~1e-15, at orders up to
// 2·10⁴ + 1.
#pragma once

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

// Pₙ(μ) and Pₙ₋₁(μ) at μ = 1 − 2s by Bonnet's recurrence.  For μ >= ½ it runs on
// the differences Dₖ = Pₖ − Pₖ₋₁ (Reinsch's modification for arguments near 1):
//     Dₖ₊₁ = (k Dₖ − 2s (2k+1) Pₖ) / (k+1),   Pₖ₊₁ = Pₖ + Dₖ₊₁,
// which follows from Bonnet's form by subtracting (k+1)Pₖ.  The plain form
// subtracts terms ~2k·Pₖ and ~k·Pₖ₋₁ to leave ~Pₖ, and its rounding then grows
// to ~n·ε near μ = 1 — 7e-13 at n = 2001, i.e. 6e-13 relative in the first
// node θ₁ ≈ 2.4/n and 6e-9 in its weight; the difference form keeps both at
// the level of a few ε.
// Also returns μPₙ − Pₙ₋₁ (= sin θ/n · dPₙ/dθ), formed without cancellation.
template <class Real>
void legendre_pair(std::size_t n, const Real& s, Real& pn, Real& pn1, Real& mu_pn_minus_pn1) {
  if (n == 0) {
    pn = 1;
    pn1 = 0;
    mu_pn_minus_pn1 = 1;
    return;
  }
  Real p_prev = 1, p = 1 - 2 * s;  // P₀, P₁
  if (s <= Real(0.25)) {
    Real d = -2 * s;  // D₁ = P₁ − P₀
    for (std::size_t k = 1; k < n; ++k) {
      d = (Real(k) * d - 2 * s * Real(2 * k + 1) * p) / Real(k + 1);
      p_prev = p;
      p += d;
    }
    pn = p;
    pn1 = p_prev;
    mu_pn_minus_pn1 = d - 2 * s * p;  // μPₙ − Pₙ₋₁ = Dₙ − 2sPₙ
    return;
  }
  {
    for (std::size_t k = 1; k < n; ++k) {
      const Real mu_p = p - 2 * s * p;
      const Real next = (Real(2 * k + 1) * mu_p - Real(k) * p_prev) / Real(k + 1);
      p_prev = p;
      p = next;
    }
  }
  pn = p;
  pn1 = p_prev;
  mu_pn_minus_pn1 = (p - 2 * s * p) - p_prev;
}

// One node by Newton's method in θ, starting from theta; returns the final θ and
// sets the weight.
//
// The weight is taken as w = 2/(dPₙ/dθ)² with dPₙ/dθ = n(μPₙ − Pₙ₋₁)/sin θ
// (A&S 25.4.29 written in θ), evaluated at the computed node.  At an exact node
// this equals 2 sin²θ/(n Pₙ₋₁)², but the latter changes by n·δθ/|Pₙ₋₁| relative
// under a node error δθ (1e-12 at the first node of order 2001, where
// Pₙ₋₁ ~ 1e-3), whereas dPₙ/dθ is stationary up to cot θ·δθ (Legendre's equation
// gives d²Pₙ/dθ² = −cot θ dPₙ/dθ at a zero), i.e. a few ε relative.  The final
// evaluation runs in x87 extended precision for double (one more O(n) pass) so
// that the rounding of the recurrence does not enter the weight either.
template <class Real>
Real newton_node(std::size_t n, Real theta, Real& weight) {
  using std::abs;
  using std::sin;
  const Real eps = std::numeric_limits<Real>::epsilon();
  const int max_steps = std::is_same_v<Real, double> ? 12 : 8;
  Real pn, pn1, dn;
  for (int step = 0;; ++step) {
    const Real half_sin = sin(theta / 2);
    const Real s = half_sin * half_sin;
    legendre_pair(n, s, pn, pn1, dn);
    const Real delta = pn * sin(theta) / (Real(n) * dn);
    theta -= delta;
    if (abs(delta) <= 4 * eps * theta || step == max_steps) break;
  }
  using Wide = std::conditional_t<std::is_same_v<Real, double>, long double, Real>;
  const Wide half_sin = sin(Wide(theta) / 2), s = half_sin * half_sin;
  Wide wn, wn1, wd;
  legendre_pair<Wide>(n, s, wn, wn1, wd);
  const Wide sin2 = 4 * s * (1 - s);
  weight = Real(2 * sin2 / (Wide(n) * Wide(n) * wd * wd));
  return theta;
}

template <class Real>
HalfGaussLegendre<Real> half_gauss_legendre(std::size_t n) {
  if (n == 0) throw std::invalid_argument("Gauss-Legendre rule: order must be >= 1");
  HalfGaussLegendre<Real> rule;
  rule.order = n;
  const std::size_t half = n / 2;
  rule.s.resize(half + (n % 2));
  rule.w.resize(half + (n % 2));
  std::vector<double> start(half);
  if constexpr (std::is_same_v<Real, double>) {
    for (std::size_t k = 1; k <= half; ++k)
      start[k - 1] = boost::math::constants::pi<double>() * double(4 * k - 1) / double(4 * n + 2);
  } else {
    // Double nodes first: Newton in Real then needs ~2 steps instead of ~6.
    const HalfGaussLegendre<double> d = half_gauss_legendre<double>(n);
    for (std::size_t k = 0; k < half; ++k) start[k] = 2 * std::asin(std::sqrt(d.s[k]));
  }
  for (std::size_t k = 0; k < half; ++k) {
    // Tricomi's guess numbers the nodes from θ ≈ 0 upwards.
    Real w;
    const Real theta = newton_node<Real>(n, Real(start[k]), w);
    using std::sin;
    const Real half_sin = sin(theta / 2);
    rule.s[k] = half_sin * half_sin;
    rule.w[k] = w;
  }
  if (n % 2) {
    // μ = 0 is a node of every odd order: w = 2/(n Pₙ₋₁(0))², halved (see above).
    using Wide = std::conditional_t<std::is_same_v<Real, double>, long double, Real>;
    Wide pn, pn1, dn;
    legendre_pair<Wide>(n, Wide(0.5), pn, pn1, dn);
    rule.s[half] = Real(0.5);
    rule.w[half] = Real(1 / (Wide(n) * Wide(n) * pn1 * pn1));
  }
  return rule;
}

}  // namespace attenuvis::mie::detail
