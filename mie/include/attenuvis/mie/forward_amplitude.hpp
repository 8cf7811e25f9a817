// The forward-scattering amplitude S(0) continued to complex size parameter.
//
// For a real size parameter x, Q_ext = 4 Re S(0) / x² (optical theorem,
// Bohren & Huffman 1983, eq. 4.76), with
//
//     S(0) = ½ Σₙ (2n+1) (aₙ + bₙ)                          (B&H eq. 4.74, θ = 0).
//
// The Mie coefficients are meromorphic in x; for a passive sphere (Im m ≥ 0,
// time factor e^{−iωt}) their poles, the sphere's quasi-normal modes, lie in
// the lower half-plane, and S(0) is analytic in Im x ≥ 0 (forward scattering
// is causal: Bohren & Huffman Sec. 2.9; Nussenzveig 1992, "Diffraction effects
// in semiclassical scattering", ch. 2).  That is what lets the size-distribution
// integral of Q_ext be taken along a path above the real axis, where the
// resonances of nearly lossless drops are smoothed out (weather/contour_extinction).
//
// Why a separate routine from sphere(): in the upper half-plane each term
// aₙ grows like e^{2 Im x} while S(0) does not, so the sum cancels by about
// e^{2 Im x}.  The recurrences therefore run in long double (64-bit
// significand) and the result carries `magnitude` = ½ Σ (2n+1)(|aₙ| + |bₙ|),
// from which a caller bounds the rounding error (terms × ε_long double ×
// magnitude).  Keep Im x below ~8 (e^{16} ≈ 1e7) for double-level accuracy.
//
// Method: Dₙ(z) = ψₙ'(z)/ψₙ(z) at z = x and z = mx by downward recurrence
// started from Lentz's continued fraction (lentz.hpp); ξₙ(x) = x hₙ⁽¹⁾(x)
// through the ratio qₙ = ξₙ/ξ_{n−1} upward (stable for the outgoing Hankel
// function); ψₙ/ξₙ as a running product, so nothing overflows:
//
//     aₙ = (ψₙ/ξₙ) (Aₙ − ψ_{n−1}/ψₙ) / (Aₙ − ξ_{n−1}/ξₙ),  Aₙ = Dₙ(mx)/m + n/x,
//     bₙ = likewise with Bₙ = m Dₙ(mx) + n/x                  (B&H eq. 4.88).
//
// Aₙ − ψ_{n−1}/ψₙ = Dₙ(mx)/m − Dₙ(x) cancels as m → 1: the relative accuracy
// is ~ε_long double/|m − 1|, so this routine asks |m − 1| ≥ 1e-6.
#pragma once

#include <complex>
#include <cstddef>

namespace attenuvis::mie {

struct ForwardAmplitude {
  std::complex<double> s0;  // S(0) = ½ Σ (2n+1)(aₙ + bₙ)
  double magnitude = 0;     // ½ Σ (2n+1)(|aₙ| + |bₙ|): the scale of the rounding error
  std::size_t terms = 0;    // terms summed (until they stopped changing the sum)
};

// Throws std::invalid_argument unless 0 < |x| <= 1e5, Re x > 0, 0 <= Im x <= 20,
// Re m > 0, Im m >= 0 and |m - 1| >= 1e-6 (all finite).
ForwardAmplitude forward_amplitude(std::complex<double> x, std::complex<double> m);

}  // namespace attenuvis::mie
