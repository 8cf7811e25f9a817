// attenuvis::mie — Lorenz–Mie scattering by a homogeneous sphere.
//
// Conventions (Bohren & Huffman 1983, "Absorption and Scattering of Light by
// Small Particles", ch. 4; referred to as B&H below):
//  * Time dependence e^{-iωt}.  The relative refractive index is m = n + ik with
//    k >= 0 for an absorbing sphere (B&H's sign).  Wiscombe's MIEV0 and his
//    1979 report publish m = n − ik (time dependence e^{+iωt}); efficiencies
//    and g do not depend on the sign, but S1, S2, aₙ, bₙ are complex
//    conjugates of MIEV0's — conjugate them before comparing.
//  * Size parameter x = 2πr/λ with λ the wavelength in the surrounding medium;
//    m is the sphere's index divided by the medium's.
//  * Efficiencies are cross sections divided by the geometric cross section πr²:
//      Qext = (2/x²) Σ (2n+1) Re(aₙ+bₙ)                  (B&H 4.62)
//      Qsca = (2/x²) Σ (2n+1) (|aₙ|²+|bₙ|²)              (B&H 4.61)
//      Qabs = Qext − Qsca, computed from a sum of its own (each term is
//             −Im(·)/|·|², see mie/src/series.hpp) so it keeps full relative
//             accuracy even when k is tiny and Qabs ≪ Qsca.
//      Qback = 4|S1(π)|²/x² = (1/x²) |Σ (2n+1)(−1)ⁿ(aₙ−bₙ)|²  (B&H 4.82).
//             This is B&H's (and MIEV0's) backscattering efficiency.  Draine's
//             BHMIE returns Qback/(4π) (a "per steradian" value); multiply its
//             figure by 4π to compare.
//      g    = <cos θ>, the asymmetry parameter (B&H 4.74); Qpr = Qext − g Qsca
//             is the radiation-pressure efficiency (B&H 4.77).
//  * Amplitudes S1(θ), S2(θ) are B&H's (4.74): S1 = Σ (2n+1)/(n(n+1)) (aₙπₙ+bₙτₙ),
//    S2 = Σ (2n+1)/(n(n+1)) (aₙτₙ+bₙπₙ); S1(0) = S2(0) and Qext = 4 Re S1(0)/x².
//    θ is the scattering angle in degrees (0 = forward).
//  * aₙ, bₙ are B&H's (4.53); a perfectly conducting sphere is the limit
//    |m| → ∞ : aₙ = ψₙ'(x)/ξₙ'(x), bₙ = ψₙ(x)/ξₙ(x).
//
// Domain (checked; outside it std::invalid_argument names the value and the
// range):  1e-8 <= x <= 1e6,  0 <= n <= 1e6,  0 <= k <= 1e6,  |m| >= 0.5.
// Within 1e-10 of the 50-digit referee for x in [1e-8, 1e6], n in [0, 10],
// k in [0, 1000] (tests/mie/test_mie_referee.cpp; m = ik included); larger |m|
// (up to 1e6) tends to the perfect conductor, checked to 1e-4 at |m| = 1.4e6.
// Outside, the recurrences fail rather than degrade (x < 1.4e-154: x² = 0;
// |m| ~ 1e154: |m x|² overflows; m -> 0).  For x below 1e-8 the Rayleigh form
// a₁ = −(2i/3) x³ (m²−1)/(m²+2) is exact to O(x²|m|²) (B&H §5.1).
// Everything is computed from ratio/logarithmic-derivative recurrences, so
// nothing overflows or underflows inside the domain.
// The numerical method and its traps (named pitfalls) are described in
// mie/src/series.hpp.
#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <vector>

#include "attenuvis/mie/forward_amplitude.hpp"
#include "attenuvis/mie/precision.hpp"

namespace attenuvis::mie {

// Complex<Real>: the complex type that goes with a real floating type.  Other
// real types (the 50-digit referee) specialise ComplexOf in their own header.
template <class Real>
struct ComplexOf {
  using type = std::complex<Real>;
};
// The complex type of a real type: std::complex<double>, or the referee's.
template <class Real>
using Complex = typename ComplexOf<Real>::type;

// Efficiencies of one sphere (cross sections over πr², see above) and the term count.
template <class Real>
struct Efficiencies {
  Real qext{}, qsca{}, qabs{}, qback{}, qpr{}, g{};
  std::size_t terms = 0;  // number of series terms summed (n = 1..terms)
};

// How many terms of the series are summed.
enum class TermRule {
  // Default: keep adding terms (beyond n > x) until the next one is below
  // ~1e-4·ε of every accumulated sum, ε the unit round-off of Real.  This is
  // what keeps Qback and absorbing spheres within 1e-10 of the exact value.
  converged,
  // Wiscombe (1980, Appl. Opt. 19:1505, eq. 19) / MIEV0: N = x + 4.05 x^{1/3} + 2
  // (truncated to an integer).  Provided to reproduce other codes and to
  // measure its truncation error; it is NOT accurate to 1e-10 (trap truncation,
  // mie/src/series.hpp).
  wiscombe,
};

// Working precision of the recurrences for ψₙ(x), ψₙ(mx) ratios (Precision,
// attenuvis/mie/precision.hpp); each term's own arithmetic is always double.
// Unset (the default, "automatic"): double where the 50-digit referee shows
// double to be enough, x87 extended (long double, 64-bit significand)
// elsewhere, i.e. extended for
//   * x > 1e4: the rounding errors of the recurrences add up to ~√N·ε in
//     every aₙ and Qback, an alternating sum cancelling by ~x, amplifies them
//     (double: ~1e-11 at x = 1e5, m = 1.33, against 2e-13);
//   * |m − 1| < 5e-5: at a zero of ψₙ(x) (e.g. x = 4.493409457909064) with
//     m = 1 + 1e-6 the difference recurrence inherits the cancellation of
//     ψₙ₊₁/ψₙ (double: 8e-11 in Qext);
//   * |m − 1| < 1e-2 and x > 1e3: Qback ~ 1e-9 Qext, whose relative error in
//     double grows with x (1e-11 at x = 1e4);
// and never below x <= extended_above.  The thresholds and measurements are
// in src/sphere_checks.hpp.
//   Precision::double_precision  fast mode: everything in double (error grows
//                                with x, see the benchmark)
//   Precision::extended          extended recurrences at every x
struct Options {
  TermRule terms = TermRule::converged;
  std::optional<Precision> precision;  // unset: automatic (see above)
  double extended_above = 0.0;         // automatic: double-only at x <= this
};

// Extra outputs of scatter(): the Mie coefficients and/or the amplitude
// functions at the given scattering angles (degrees).
struct Extras {
  bool coefficients = false;
  std::vector<double> angles_deg;
};

// What scatter() returns: the efficiencies and, as asked in Extras, the
// coefficients aₙ, bₙ and the amplitudes S1, S2 at the requested angles.
template <class Real>
struct Scattering {
  Efficiencies<Real> q;
  std::vector<Complex<Real>> a, b;   // aₙ, bₙ for n = 1..q.terms at index n-1 (if requested)
  std::vector<double> angles_deg;    // copy of the request
  std::vector<Complex<Real>> s1, s2; // S1(θ), S2(θ), one per angle
};

// Tag for a perfectly conducting (|m| → ∞) sphere.
struct PerfectConductor {};

// Efficiencies of a homogeneous sphere with size parameter x > 0 and relative
// refractive index m = n + ik (n >= 0, k >= 0, m != 0; n = 0 is a purely
// imaginary index, e.g. a lossless Drude metal below its plasma frequency).
// Throws std::invalid_argument outside the domain above (x outside
// [1e-8, 1e6], n or k outside [0, 1e6], |m| < 0.5, non-finite input).  For many spheres, spheres() (attenuvis/mie/spheres.hpp)
// returns the same values several times faster.
Efficiencies<double> sphere(double x, std::complex<double> m, const Options& options = {});
Efficiencies<double> sphere(double x, PerfectConductor, const Options& options = {});

// The same, plus the coefficients and/or amplitudes asked for in `extras`.
Scattering<double> scatter(double x, std::complex<double> m, const Extras& extras,
                           const Options& options = {});
Scattering<double> scatter(double x, PerfectConductor, const Extras& extras,
                           const Options& options = {});

// Wiscombe's term count N = floor(x + 4.05 x^{1/3} + 2) (see TermRule::wiscombe).
std::size_t wiscombe_terms(double x);

}  // namespace attenuvis::mie
