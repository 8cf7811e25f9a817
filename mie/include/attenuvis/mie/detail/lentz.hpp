// Continued fraction for the ratio of Bessel functions J_{ν-1}(z)/J_ν(z),
// evaluated by the modified Lentz algorithm.
//
// Template detail of the Mie core: the start of the downward recurrences of
// the series (log_derivative.hpp); forward_amplitude()
// (mie/src/forward_amplitude.cpp) runs the same fraction on vector lanes.
//
// From the recurrence J_{ν-1}(z) + J_{ν+1}(z) = (2ν/z) J_ν(z):
//     J_{ν-1}/J_ν = b₀ − 1/(b₁ − 1/(b₂ − …)),   b_j = 2(ν+j)/z.
// Lentz (1976, Appl. Opt. 15:668) evaluates it forwards, without guessing a
// starting index; the "modified" form (Thompson & Barnett 1986, J. Comput.
// Phys. 64:490) replaces a zero denominator by a tiny number.  For Riccati–
// Bessel functions ψₙ(z) = z jₙ(z) = √(πz/2) J_{n+½}(z), so with ν = n + ½ this
// gives ψ_{n-1}(z)/ψₙ(z) = Dₙ(z) + n/z, the quantity every recurrence in the
// core starts from (trap start-value in series.hpp: a wrong start value for
// the downward recurrence of Dₙ(mx) is not forgotten for large, weakly
// absorbing spheres).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "attenuvis/mie/detail/complex_ops.hpp"

namespace attenuvis::mie::detail {

// ψ_{n-1}(z)/ψₙ(z) for complex or real z (type T), n >= 1.  z enters only
// through k_over_z(k) = k/z for integer k (see ScaledInverse in
// log_derivative.hpp: it keeps the phase of large z accurate).
template <class T, class Real, class KOverZ>
T riccati_psi_ratio(std::size_t n, const KOverZ& k_over_z) {
  const Real eps = std::numeric_limits<Real>::epsilon();
  const Real eps2 = eps * eps;
  const Real tiny = (std::numeric_limits<Real>::min)() * Real(1e20);
  // b_j = 2(ν+j)/z = (2n+1+2j)/z.
  T f = k_over_z(index_real<Real>(2 * n + 1));
  if (f == T(Real(0))) f = T(tiny);
  T c = f;
  T d = T(Real(0));
  // Enough for every case the core hands to it (see choose_method in
  // series.hpp); the bound only stops a runaway loop.
  const std::size_t max_iterations = 400000000;
  for (std::size_t j = 1; j <= max_iterations; ++j) {
    const T b = k_over_z(index_real<Real>(2 * n + 1 + 2 * j));
    d = b - d;
    if (d == T(Real(0))) d = T(tiny);
    c = b - inv<Real>(c);
    if (c == T(Real(0))) c = T(tiny);
    d = inv<Real>(d);
    const T delta = mul<Real>(c, d);
    f = mul<Real>(f, delta);
    if (mag2<Real>(delta - T(Real(1))) < eps2) return f;
  }
  throw std::runtime_error("attenuvis::mie: Lentz continued fraction did not converge for n=" +
                           std::to_string(n));
}

}  // namespace attenuvis::mie::detail
