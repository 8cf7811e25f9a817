// Product integration across one resonance: the weights of
//
//     int_a^b F(x) / |x - x_p|^2 dx,   x_p = x0 - i gamma,  x0 in [a, b],
//
// for F smooth on [a, b], by Clenshaw-Curtis with the weight taken exactly
// (Piessens & Branders; QUADPACK's QC25C does the same for the Cauchy weight
// 1/(x - c), Piessens et al. 1983, "QUADPACK", Sec. 2.2.3).  Near a pole of
// a Mie coefficient c(x) = R/(x - x_p) + h(x), every bulk integrand q(x) is a
// Hermitian form in the coefficients, so
//
//     q(x) |x - x_p|^2 = M |R|^2 + 2 Re(R* (x - x_p) B(x)) + s(x) |x - x_p|^2
//
// with M, B and s smooth (bulk_optics.hpp): F = q w |x - x_p|^2 is smooth
// however narrow the resonance, and the rule integrates the peak of width
// gamma with N + 1 = 25 evaluations, where a rule that samples it would need
// panels graded down to gamma (~20 panels for gamma = 1e-9).
//
// F is interpolated at the Chebyshev points t_j = cos(j pi / N) of [a, b]
// (x = mid + half t) and the interpolant p_N = sum'' c_k T_k is integrated
// against the weight:  int F W dx ~ (1/half) sum'' c_k mu_k,
//
//     mu_k = int_-1^1 T_k(t) dt / ((t - t0)^2 + g^2),  t0 = (x0 - mid) / half,  g = gamma / half.
//
// The modified moments mu_k are integrals of smooth functions once the
// interval is cut at t0 and graded away from it ([t0, t0 + g], then pieces
// four times longer each): 16-point Gauss-Legendre on every piece, where the
// weight's poles t0 +- i g lie at least a piece's half-length away, is exact
// to rounding (the Bernstein ellipse of each piece excludes them with
// rho >= 2.4, rho^-32 < 1e-12).  (The forward recurrence of the Cauchy
// moments, as QUADPACK's QC25C runs it for real poles, loses ~k log10 rho
// digits once the pole leaves the interval by g: a broad resonance on a small
// panel.)  At most ~2 log4(2/g) + 2 pieces: 36 for g = 1e-10.
//
// The error estimate is the difference from the same construction on the 13
// points j even (N = 12), as QC25C; it is reliable when the interpolant
// converges, i.e. when nothing else sharp lies within the panel (another
// resonance that was not given a panel of its own is bounded, bulk_optics.hpp,
// and a node that lands on one shows in the difference).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>

#include "attenuvis/io/check.hpp"

namespace attenuvis::weather::detail {

constexpr int kPoleRuleIntervals = 24;                 // N: 25 Chebyshev points
constexpr int kPoleRulePoints = kPoleRuleIntervals + 1;

struct PoleRule {
  std::array<double, kPoleRulePoints> x{};       // the nodes, x_j = mid + half cos(j pi / N)
  std::array<double, kPoleRulePoints> fine{};    // weights of F(x_j), N = 24
  std::array<double, kPoleRulePoints> coarse{};  // N = 12 on the even j (0 at odd j)
};

// mu_k, k = 0..n, for the pole at t0 + i g, by graded Gauss-Legendre pieces
// on either side of t0 (see above).
template <int n>
std::array<double, n + 1> lorentzian_chebyshev_moments(double t0, double g) {
  using Rule = boost::math::quadrature::gauss<double, 16>;
  std::array<double, n + 1> mu{};
  // A piece [lo, hi] of s = t - t0 (the offset carried by itself: near t0 it
  // keeps its relative precision, which t = t0 + s would lose).
  auto piece = [&](double lo, double hi) {
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (std::size_t i = 0; i < Rule::abscissa().size(); ++i)
      for (double sign : {-1.0, 1.0}) {
        const double offset = mid + sign * Rule::abscissa()[i] * half, t = t0 + offset;
        const double w = Rule::weights()[i] * half / (offset * offset + g * g);
        double prev = 1, cur = t;  // T_0, T_1
        mu[0] += w;
        if (n >= 1) mu[1] += w * t;
        for (int k = 2; k <= n; ++k) {
          const double next = 2 * t * cur - prev;
          prev = cur;
          cur = next;
          mu[k] += w * cur;
        }
      }
  };
  // Right of t0: s in [0, g], then lengths 4g, 16g, ... up to 1 - t0; left alike.
  for (double direction : {1.0, -1.0}) {
    const double end = direction > 0 ? 1.0 - t0 : -1.0 - t0;
    double at = 0, length = g;
    while (direction * (end - at) > 0) {
      const double next = direction > 0 ? std::min(at + length, end) : std::max(at - length, end);
      piece(std::min(at, next), std::max(at, next));
      at = next;
      length *= 4;
    }
  }
  return mu;
}

// Weights of sum'' c_k mu_k / half written on the values F(t_j) of n + 1
// Chebyshev points (n = 24 or 12), mu_k for the pole at t0 + i g.
template <int n>
std::array<double, n + 1> chebyshev_product_weights(double t0, double g, double half) {
  const double pi = boost::math::constants::pi<double>();
  const std::array<double, n + 1> mu = lorentzian_chebyshev_moments<n>(t0, g);
  std::array<double, n + 1> w{};
  for (int j = 0; j <= n; ++j) {
    double sum = 0;
    for (int k = 0; k <= n; ++k) {
      const double halve = (k == 0 || k == n) ? 0.5 : 1.0;
      sum += halve * std::cos(pi * double(k) * j / n) * mu[k];
    }
    const double halve_j = (j == 0 || j == n) ? 0.5 : 1.0;
    w[j] = 2.0 / n * halve_j * sum / half;
  }
  return w;
}

// The rule for the panel [a, b] (in x) and the pole x0 - i gamma, x0 in [a, b].
inline PoleRule pole_rule(double a, double b, double x0, double gamma) {
  ATTENUVIS_CHECK_LT(a, b);
  ATTENUVIS_CHECK_GT(gamma, 0.0);
  const double pi = boost::math::constants::pi<double>();
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  const double t0 = std::clamp((x0 - mid) / half, -1.0, 1.0), g = gamma / half;
  PoleRule r;
  for (int j = 0; j < kPoleRulePoints; ++j) r.x[j] = mid + half * std::cos(pi * j / kPoleRuleIntervals);
  const auto fine = chebyshev_product_weights<kPoleRuleIntervals>(t0, g, half);
  const auto coarse = chebyshev_product_weights<kPoleRuleIntervals / 2>(t0, g, half);
  for (int j = 0; j < kPoleRulePoints; ++j) r.fine[j] = fine[j];
  for (int j = 0; j <= kPoleRuleIntervals / 2; ++j) r.coarse[2 * j] = coarse[j];
  return r;
}

}  // namespace attenuvis::weather::detail
