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
// e^{2 Im x}.  The result therefore carries `magnitude` = ½ Σ (2n+1)(|aₙ| + |bₙ|)
// (bounded above through |Re| + |Im| of the factors of aₙ and bₙ), from which
// rounding_bound() = terms × unit roundoff × magnitude + 2 ε |S(0)| bounds the
// rounding error (a worst-case linear accumulation; the measured errors are
// 10-100x smaller, tests/mie/test_forward_amplitude.cpp).  Two precisions:
//   extended          long double (64-bit significand, ε = 1.1e-19), the default;
//   double_precision  ~4x faster (the x87 unit is slow).  At Im x = 4 the bound is
//             ~1e-11 |S(0)| for x ≤ 1000, enough for a 1e-9 size integral;
//             keep Im x below ~4 here (the cancellation grows like e^{2 Im x}).
// In extended arithmetic keep Im x below ~8 (e^{16} ≈ 1e7) for double-level
// accuracy.
//
// Method: Dₙ(z) = ψₙ'(z)/ψₙ(z) at z = x and z = mx by downward recurrence
// started from Lentz's continued fraction (detail/lentz.hpp); ξₙ(x) = x hₙ⁽¹⁾(x)
// through the ratio ξ_{n−1}/ξₙ upward (stable for the outgoing Hankel
// function); ψₙ/ξₙ as a running product, so nothing overflows:
//
//     aₙ = (ψₙ/ξₙ) (Dₙ(mx)/m − Dₙ(x)) / (Aₙ − ξ_{n−1}/ξₙ),  Aₙ = Dₙ(mx)/m + n/x,
//     bₙ = likewise with m Dₙ(mx) and Bₙ = m Dₙ(mx) + n/x     (B&H eq. 4.88).
//
// Dₙ(mx)/m − Dₙ(x) cancels as m → 1: the relative accuracy is ~ε/|m − 1|, so
// this routine asks |m − 1| ≥ 1e-6.
#pragma once

#include <complex>
#include <cstddef>

#include "attenuvis/mie/precision.hpp"

namespace attenuvis::mie {

// S(0) at one (complex) size parameter, with what bounds its rounding error.
struct ForwardAmplitude {
  std::complex<double> s0;  // S(0) = ½ Σ (2n+1)(aₙ + bₙ)
  double magnitude = 0;     // ½ Σ (2n+1)(|aₙ| + |bₙ|): the scale of the rounding error
  std::size_t terms = 0;    // terms summed (until they stopped changing the sum)
  double unit_roundoff = 0; // ε of the arithmetic used
  // Bound on |computed S(0) − S(0)|: terms × unit_roundoff × magnitude + 2 ε_double |S(0)|.
  double rounding_bound() const;
};

// The largest |x| forward_amplitude() takes: checked against 60-digit
// mpmath up to x = 2.8e5 (tests/data/mie/forward_amplitude_mpmath_large.csv).
inline constexpr double kForwardAmplitudeMaxX = 3e5;

// Throws std::invalid_argument unless 0 < |x| <= kForwardAmplitudeMaxX, Re x > 0, 0 <= Im x <= 20,
// Re m > 0, Im m >= 0 and |m - 1| >= 1e-6 (all finite).
ForwardAmplitude forward_amplitude(std::complex<double> x, std::complex<double> m,
                                   Precision precision = Precision::extended);

// S(0) at x[0..count) for one m, the same values as forward_amplitude() one by
// one (within their rounding bounds), about 5-7x faster in double on a CPU
// with AVX-512: sixteen series run side by side (eight for a call of eight
// points or fewer; the tables take 51 MB per thread at |x| = 1e5, 153 MB at 3e5),
// compiled per instruction set, so that their divisions overlap and
// vectorise, and the continued fractions that start them run side by side
// too.  Points of similar |x| batch best (the tables run to the largest).
// Same argument checks, before any work.
void forward_amplitudes(const std::complex<double>* x, std::size_t count, std::complex<double> m,
                        Precision precision, ForwardAmplitude* out);

}  // namespace attenuvis::mie
