// The resonances of a nearly lossless sphere: the poles of the Mie coefficients
// aₙ(x), bₙ(x) just below the real size-parameter axis.
//
// Morphology-dependent resonances (quasi-normal modes) of a sphere of index
// m = n + ik, n > 1: a partial wave of order ν = n_order + ½ whose size
// parameter lies in the centrifugal barrier, x < ν < n x, is trapped inside
// the sphere and leaks out by tunnelling.  aₙ (or bₙ) then has a pole
// x_p = x₀ − iγ close to the real axis,
//
//     c(x) = R / (x − x_p) + h(x),   c = aₙ or bₙ,  h analytic near x_p,
//
// so that on the real axis c, |c|² and every quantity built from them carry
// a peak of half-width γ = γ_rad + γ_abs (tunnelling plus absorption,
// γ_abs ≈ k x / n) and weight |R| ≈ γ_rad (the peak of |c| is |R|/γ <= 1) (Johnson 1993, J. Opt. Soc. Am. A 10, 343; Lam,
// Leung & Young 1992, J. Opt. Soc. Am. B 9, 1585).  γ_rad falls
// exponentially with the depth under the barrier: for water at x ~ 500 the
// modes range from γ ~ 0.1 down to 1e-70.
//
// How they are found.  Divide the denominators of aₙ and bₙ (B&H 4.53) by
// ψₙ(mx) ξₙ(x):
//
//     aₙ:  F(x) = m Gₙ(x) − Dₙ(mx),     bₙ:  F(x) = Gₙ(x) − m Dₙ(mx),
//
// Gₙ = ξₙ'/ξₙ, Dₙ = ψₙ'/ψₙ; the poles are the zeros of F.  For the lossless
// index n_r = Re m and real x in the barrier, ξₙ ≈ −iχₙ up to the tunnelling
// factor ψₙ/χₙ, and the real function
//
//     F_r(x) = n_r Cₙ(x) − Dₙ(n_r x)   (aₙ),   Cₙ(x) − n_r Dₙ(n_r x)   (bₙ),   Cₙ = χₙ'/χₙ,
//
// vanishes at the resonance position x₀.  In the barrier Cₙ is smooth and
// increasing (χₙ has no zeros below ν) and Dₙ(n_r x) falls from +∞ to −∞
// between consecutive zeros of ψₙ(n_r x) (D' = n(n+1)/z² − 1 − D² < 0 for
// z > ν), so F_r rises from −∞ to +∞ on each such branch and has exactly one
// zero there: the resonances of order n in the barrier are in one-to-one
// correspondence with the branches of Dₙ(n_r x), i.e. with the zeros of
// ψₙ(n_r x) (radial order l ↔ l-th zero).  resonance_brackets() scans x on a
// grid of step min(0.5, 1/n_r) (less than half the spacing π/n_r of the zeros
// of ψₙ(n_r x)), every order at once (one downward recurrence for Dₖ(n_r x),
// one upward for χₖ(x) per grid point), and brackets each zero of F_r by the
// signs of F_r and of ψₙ(n_r x) at consecutive grid points.  Above the
// barrier (x > ν − ½) the modes are broad (γ ≳ 0.05 for water, measured),
// resolved by any rule that samples the ripple, and are not reported.
//
// locate_resonance() refines a bracket: the zero x₀ of F_r by safeguarded
// Newton (F_r' from the Riccati equations, Cₙ' = n(n+1)/x² − 1 − Cₙ² and
// likewise for D), then the complex zero x_p of F with the complex index by
// Newton from x₀, and the residue
//
//     R = (ψₙ/ξₙ)(x_p) (m Dₙ(x_p) − Dₙ(m x_p)) / F'(x_p)        (aₙ),
//     R = (ψₙ/ξₙ)(x_p) (Dₙ(x_p) − m Dₙ(m x_p)) / F'(x_p)        (bₙ),
//
// since aₙ = (ψₙ/ξₙ)(m Dₙ(x) − Dₙ(mx)) / F(x) (and bₙ alike).  All functions
// come from ratio recurrences (D downward from Lentz's continued fraction, ξ
// upward), nothing overflows.  In double the pole is located to ~n ε |x|
// (1e-13 at x ~ 1000), so a half-width below ~1e-11 is known to a few percent
// at best; such modes carry weight |R| ≈ γ_rad of the same order.
//
// Cost: the scan is O(x_hi²) (0.05 s for x up to 1700 on one core); each
// located resonance O(n) per Newton step, ~10 steps.
#pragma once

#include <complex>
#include <vector>

namespace attenuvis::mie {

// Which coefficient a resonance is a pole of.
enum class ResonanceMode { electric, magnetic };  // a pole of aₙ (TM), of bₙ (TE)

// A resonance of the lossless sphere bracketed on the real axis: its order,
// mode, an interval [x_lo, x_hi] holding the zero of F_r, and an estimate of
// its radiative half-width from the tunnelling factor at the top of the
// bracket, |ψₙ(x_hi)/χₙ(x_hi)| |num| / |F_r'| (see .cpp), which the located
// residue does not exceed (checked in tests/mie/test_resonances.cpp).
struct ResonanceBracket {
  int order = 0;
  ResonanceMode mode = ResonanceMode::electric;
  double x_lo = 0, x_hi = 0;
  double width_estimate = 0;
  // The branch of Dₙ(n_r x) that holds the zero: the sign of ψₙ(n_r x) on it,
  // and whether it is the branch of x_lo (a zero of ψₙ may lie between x_lo
  // and x_hi; F_r jumps from +∞ to −∞ there).
  int branch_sign = 1;
  bool branch_holds_lo = true;
};

// Every resonance of the lossless sphere of index n_r = index (> 1) in the
// barrier, x₀ < ν − ½, with x₀ in [x_lo, x_hi], in increasing order of x_lo.
// Throws std::invalid_argument unless 0 < x_lo <= x_hi <= 1e5 and
// 1 < index <= 10.  Nothing for index <= 1 would be the honest answer (no
// barrier), but callers are expected to know that: they ask only for water.
std::vector<ResonanceBracket> resonance_brackets(double index, double x_lo, double x_hi);

// One located resonance: its order, mode, pole and residue.
struct Resonance {
  int order = 0;
  ResonanceMode mode = ResonanceMode::electric;
  std::complex<double> pole;     // x_p = x₀ − iγ
  std::complex<double> residue;  // R: c(x) = R / (x − x_p) + regular part
  double half_width() const { return -pole.imag(); }
};

// The pole and residue of a bracketed resonance for the index m (Re m the
// bracket's index, 0 <= Im m <= 1e-2).  Throws std::runtime_error naming the
// order and bracket when Newton does not converge.
Resonance locate_resonance(const ResonanceBracket& bracket, std::complex<double> m);

}  // namespace attenuvis::mie
