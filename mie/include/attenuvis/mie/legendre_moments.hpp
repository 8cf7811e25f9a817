// Legendre moments of a sphere's phase function and the generalised-spherical-
// function expansion of its whole scattering matrix — the single-scattering
// input of (polarised) radiative-transfer solvers.
//
// Normalisation.  p(μ) is the phase function with ∫ p dΩ = 4π (see
// scattering_matrix.hpp), μ = cos θ, and
//     p(μ) = Σ_{l=0}^{2N} (2l+1) χ_l P_l(μ),     χ_l = ½ ∫₋₁¹ p(μ) P_l(μ) dμ,
// so χ₀ = 1, χ₁ = g (the asymmetry parameter) and |χ_l| <= 1.  With N series
// terms S1, S2 are polynomials of degree N in μ and χ_l = 0 exactly for l > 2N.
//
// Relation to other codes:
//  * DISORT (Stamnes et al. 1988) takes PMOM(K) = ½ ∫ p P_K dμ with PMOM(0) = 1,
//    i.e. exactly χ_l (DISORT's GETMOM gives Rayleigh PMOM(2) = 0.1 and
//    Henyey–Greenstein PMOM(K) = g^K, the same convention).  Pass χ_0…χ_NMOM.
//  * MIEV0 (Wiscombe 1979/1996) returns PMOM(L) with PQ(μ) = Σ (2L+1) PMOM(L) P_L(μ)
//    for the UNNORMALISED quantities PQ; with IPOLZN = 0, PQ = (|S1|²+|S2|²)/2 = S11,
//    so PMOM(0) = x² Qsca / 4 and
//        χ_l = PMOM(l) / PMOM(0) = 4 PMOM(l) / (x² Qsca).
//    With IPOLZN = 1234 its four columns are the moments of |S1|², |S2|²,
//    Re(S1 S2*) and −Im(S1 S2*) in MIEV0's own sign convention (m = n − ik, its
//    S1, S2 are the complex conjugates of ours); then
//        χ_l  = (PMOM(l,1) + PMOM(l,2)) / (PMOM(0,1) + PMOM(0,2)),
//        α4_l = (2l+1) · 2 PMOM(l,3) / (PMOM(0,1) + PMOM(0,2)).
//  * Mishchenko's spher.f / T-matrix codes print α1…β2 below (α1_l = (2l+1) χ_l).
//
// Polarised expansion (de Rooij & van der Stap 1984, A&A 131:237; Mishchenko,
// Travis & Lacis 2002, "Scattering, Absorption, and Emission of Light by Small
// Particles" (MTL), §4.11, eqs. 4.75–4.80).  The normalised scattering matrix of
// a sphere, in the notation of MTL, is
//     a1 = a2 = p = 2 S11/W,   a3 = a4 = 2 S33/W,   b1 = 2 S12/W,   b2 = −2 S34/W,
// with B&H's S11, S12, S33, S34 (B&H 4.77) and W = x² Qsca / 2.  b2 has the
// opposite sign of B&H's S34 because MTL's Stokes V has the opposite sign of
// B&H's (their U agree); a1, a3, b1 have B&H's signs.  Then
//     a1(θ) = Σ α1_l d^l_{00}(θ),      a2 + a3 = Σ (α2_l + α3_l) d^l_{22}(θ),
//     a4(θ) = Σ α4_l d^l_{00}(θ),      a2 − a3 = Σ (α2_l − α3_l) d^l_{2,−2}(θ),
//     b1(θ) = Σ β1_l d^l_{02}(θ),      b2(θ)   = Σ β2_l d^l_{02}(θ),
// where d^l_{mn} are the Wigner functions as MTL's subroutine MATR evaluates
// them: d²_{22} = (1+μ)²/4, d²_{2,−2} = (1−μ)²/4, d²_{02} = (√6/4)(μ² − 1)
// (recurrences in detail/gsf_coefficients_impl.hpp).  Identities: α1_0 = 1,
// α1_1 = 3g; α2, α3, β1, β2 vanish for l < 2; |α1_l|, |α4_l|, |β1_l|, |β2_l|
// <= 2l+1 and |α2_l ± α3_l| <= 2(2l+1) (|F_ij| <= F11 and |d| <= 1); everything
// vanishes for l > 2N.  For a Rayleigh sphere (x → 0): α1 = (1, 0, ½),
// α2_2 = 3, α3 = 0, α4_1 = 3/2, β1_2 = √6/2, β2 = 0.
//
// Method: exact Gauss–Legendre quadrature of the amplitude products with
// 2N+1 nodes (detail/legendre_moments_impl.hpp), O(N²).
//
// Accuracy (tests/mie/test_legendre_moments.cpp), max over l = 0..2N of the
// absolute error of χ_l and of α_l/(2l+1), β_l/(2l+1), for m in {1.33 + 1e-8i,
// 1.5 + 0.1i, 10 + 10i}: against the 50-digit referee <= 4.5e-16 for x <= 10,
// <= 1.7e-15 at x = 100, <= 3.8e-15 at x = 1000; at x = 1e4 (N ≈ 10180), against
// the same algorithm in extended precision on the referee's coefficients (that
// rung agrees with the 50-digit referee to 1.2e-18 for x <= 1000), <= 1.9e-14
// (χ_l alone <= 1.6e-14, also against the 50-digit referee itself).
//
// Cost: at x = 1000 (N ≈ 1085) the moments take ~0.8 ms and the full expansion
// ~2.0 ms; with the Mie coefficients, 41-45x and 97-108x the efficiencies
// (~20 µs) measured in the same run (one core of the shared AMD EPYC development
// machine, validation/bench/mie_moments_speed.cpp, which also prints the error).
// The node loops run in clones per instruction set (mie/src/legendre_moments_
// double.cpp): AVX-512 3.0x faster than the baseline x86-64 build of the same
// loops at x = 1000, same bits.  The 2x one might hope for is out of reach of
// any direct method: the efficiencies are O(N) sums, whereas the 2N+1 moments
// each depend on all N coefficient pairs.  This quadrature does N(N+1) ≈ 1.2e6
// node-term updates of ~25 flops (S1, S2 at N+1 nodes) and (2N+1)(N+1) ≈ 2.4e6
// Legendre steps of ~7 (no fused multiply-adds: -ffp-contract=off), ~46 Mflop
// in 0.8 ms, ~55 Gflop/s, about the 16 flop/cycle one Zen 4 core does without
// FMA.  2x the efficiencies (~40 µs) would need ~1 Tflop/s; only a fast
// Legendre transform (O(N log² N)) could change the count — not done.  Dave's
// double sums (O(N²) per moment) cost more.  Building the rule of 2N+1 nodes
// adds ~22 ms once per order bin; rules are cached per thread for every bin met
// (orders within ~3-6% share one).
//
// Example (DISORT input for one water droplet, x = 50, m = 1.33 + 1e-8i):
//     namespace mie = attenuvis::mie;
//     mie::Extras ex; ex.coefficients = true;
//     const auto s = mie::scatter(50.0, {1.33, 1e-8}, ex);
//     const std::vector<double> chi = mie::phase_function_moments(s);
//     // N = 81 terms, so chi has 2N + 1 = 163 entries: chi[0] = 1, chi[1] = 0.850727 = s.q.g,
//     // chi[2] = 0.769771, ...; moments above 162 are exactly zero.
//     // DISORT: PMOM(K, LC) = chi[K] for K = 0..NMOM, SSALB(LC) = s.q.qsca / s.q.qext
//     const mie::ScatteringMatrixExpansion<double> e = mie::scattering_matrix_expansion(s);
//     // e.alpha1[l] == (2l+1) * chi[l] (alpha1[2] = 3.848855); e.beta1[2] = -0.017994
#pragma once

#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie {

// max_order argument meaning "every non-zero moment, l = 0..2N".
inline constexpr std::size_t all_orders = std::numeric_limits<std::size_t>::max();

// α1…α4, β1, β2 for l = 0..L (index l).
template <class Real>
struct ScatteringMatrixExpansion {
  std::vector<Real> alpha1, alpha2, alpha3, alpha4, beta1, beta2;
};

// χ_l for l = 0..L, L = min(max_order, 2N) — or exactly max_order when that is
// larger than 2N (then the entries above 2N are exact zeros).  `s` must carry the
// Mie coefficients (scatter() with extras.coefficients = true), else
// std::invalid_argument.
std::vector<double> phase_function_moments(const Scattering<double>& s, std::size_t max_order = all_orders);

// The same for the sphere (x, m), computing the coefficients itself.
std::vector<double> phase_function_moments(double x, std::complex<double> m,
                                           std::size_t max_order = all_orders);

// α1…β2 for l = 0..L, L as above.
ScatteringMatrixExpansion<double> scattering_matrix_expansion(const Scattering<double>& s,
                                                              std::size_t max_order = all_orders);

// p(θ) = Σ (2l+1) χ_l P_l(cos θ) at the given angles (degrees): the phase
// function as a radiative-transfer code rebuilds it from the moments.
std::vector<double> phase_function_from_moments(const std::vector<double>& chi,
                                                const std::vector<double>& angles_deg);

}  // namespace attenuvis::mie
