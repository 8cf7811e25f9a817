// The ratios of the downward pass for small spheres, from power series
// instead of recurrences (template-free detail of the Mie core).
//
// For |z| < π the ratio yₙ(z) = ψₙ₊₁(z)/ψₙ(z) is z fₙ(z²) with fₙ analytic in
// the disc |u| < j²ₙ₊½,₁ (its poles are the zeros of ψₙ, the first at
// z = jₙ₊½,₁ >= j½,₁ = π, DLMF §10.21(iv)).  Since ψₙ(z) = √(πz/2) Jₙ₊½(z)
// (DLMF 10.47.3), yₙ = Jₙ₊₃⁄₂/Jₙ₊½, and the partial fractions of J_{ν+1}/J_ν
// (Watson 1944 §15.41; the Rayleigh function of DLMF §10.21(viii)) give
//     yₙ(z) = Σₛ 2z/(j²ₛ − z²),   jₛ = jₙ₊½,ₛ,
// gives fₙ(u) = Σₖ φₙₖ uᵏ with φₙₖ = 2 Σₛ j⁻²⁽ᵏ⁺¹⁾ₛ > 0 and
// φₙ,ₖ₊₁ <= φₙₖ/π²: every coefficient is positive and the tail after K
// terms is at most φₙK |u|ᴷ/(1 − |u|/π²).  So at small x and |mx| the
// tables yₙ(x), yₙ(mx), δₙ = yₙ(mx) − yₙ(x) come from one short polynomial
// per order, all orders at once (vector lanes across n), instead of a chain
// of N + K dependent complex divisions (log_derivative.hpp), which at
// x = 0.1 was 40% of a call.  The Hankel ratio ρₙ = ξₙ₋₁/ξₙ is formed from
// ψₙ = ψ₀ Π yₖ and ηₙ = x yₙ(x) (the second kind, upward: stable, it is the
// dominant solution), one independent division per order.
//
// Trap m-near-1 is kept: δₙ is formed as
//     δₙ = x [ (m − 1) fₙ(u_m) + (u_m − u) fₙ[u_m, u] ],   u_m − u = (m² − 1) x²,
// with the divided difference fₙ[u_m, u] from the same Horner loop (synthetic
// division), so every part is proportional to m − 1 explicitly.
#pragma once

#include <complex>
#include <cstddef>

#include "attenuvis/mie/log_derivative.hpp"
#include "attenuvis/mie/scratch.hpp"

namespace attenuvis::mie::detail {

// Where sum_series fills its tables from the series: x <= 1.5 and |m x| <= 1.6.
// A function of (x, m) only, so that spheres() can send these spheres to
// sphere() and stay bit-identical to it (sphere_lanes.cpp).
bool in_series_domain(double x, std::complex<double> m);

// The tables series_ratios() fills (n = 0..N unless said otherwise).
struct SeriesTables {
  double* y;                   // yₙ(x)
  StoredComplex<double>* rho;  // ρₙ = ξₙ₋₁/ξₙ, n = 1..N+1
  StoredComplex<double>* w;    // δₙ, or yₙ(mx) where slot is Slot::value or is_value[n] is set
  unsigned char* is_value;     // Slot::difference only (the rule of downward_ratios)
  StoredComplex<double>* R;    // Rₙ = ψₙ/ξₙ, n = 1..N
  double* s;                   // 1/|ξₙ|², n = 1..N
};

// Fills `t` for a sphere of size x and index m (sin_x, cos_x: sin x and
// cos x).  Rₙ and 1/|ξₙ|² are formed order by order from ψₙ and ηₙ, not as
// the running products of block_inputs (series.hpp).  Returns false, having
// written nothing that is read afterwards, when N + 2 exceeds the
// coefficient table or ηₙ would leave the range where |ξₙ|² is finite; the
// caller then uses downward_ratios.  Requires in_series_domain(x, m) and
// slot != Slot::none.
bool series_ratios(double x, std::complex<double> m, std::size_t N, Slot slot, double sin_x, double cos_x,
                   const SeriesTables& t);

// The number of terms the series takes at |u| = r π² (the error bound above
// and the divided difference's), for the benchmark and the tests.
std::size_t series_ratio_terms(double r);

}  // namespace attenuvis::mie::detail
