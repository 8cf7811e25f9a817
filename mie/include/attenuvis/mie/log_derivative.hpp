// Logarithmic derivatives of Riccati–Bessel functions for the Mie series.
//
// Template implementation detail of the Mie core; included only by the
// translation units that instantiate it (mie/src/sphere_*.cpp).
//
// Notation (B&H ch. 4): ψₙ(z) = z jₙ(z), Dₙ(z) = ψₙ'(z)/ψₙ(z), and the ratio
// Pₙ(z) = ψ_{n-1}(z)/ψₙ(z) = Dₙ(z) + n/z.  From ψ_{n-1}+ψ_{n+1} = (2n+1)ψₙ/z:
//     P_{n-1}(z) = (2n-1)/z − 1/Pₙ(z)                               (downward)
//     D_{n-1}(z) = n/z − 1/(Dₙ(z) + n/z)                             (downward)
//     Dₙ(z)     = 1/(n/z − D_{n-1}(z)) − n/z,  D₀(z) = cot z           (upward)
//
// Trap 4 (m → 1).  The numerators of aₙ, bₙ contain Dₙ(mx)/m − Dₙ(x), which
// is O(m−1) and would be formed by cancellation.  We carry the difference
// Δₙ = Dₙ(mx) − Dₙ(x) through its own downward recurrence, obtained by
// subtracting the D recurrences for z = mx and z = x:
//     Δ_{n-1} = −n c + uₙ / (Pₙ(mx) Pₙ(x)),   uₙ = Δₙ − n c,   c = (m−1)/(m x)
// (since n/(mx) − n/x = −n c and Pₙ(mx) − Pₙ(x) = uₙ).  Every term is
// proportional to (m−1) explicitly, so nothing cancels, and Pₙ(mx), Pₙ(x) come
// from their own recurrences (not Pₙ(x)+uₙ, which would cancel near poles).
// Errors in Δ are damped exactly as errors in Dₙ(mx) are.
//
// Trap 2 (start value).  Both recurrences start at the top index N from the
// exact values given by Lentz's continued fraction (lentz.hpp), never from 0.
// Trap 5 (large k·x).  Only ratios appear; nothing grows like e^{kx}.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "attenuvis/mie/lentz.hpp"

namespace attenuvis::mie::detail {

// Replace an exact zero (a pole of the next step) by a tiny number.  Exact
// zeros are possible only by accident of rounding, but must not become inf.
template <class T, class Real>
inline void avoid_zero(T& v) {
  if (v == T(Real(0))) v = T((std::numeric_limits<Real>::min)() * Real(1e20));
}

// Downward pass from index N: fills p[n] = Pₙ(x) and delta[n] = Δₙ for
// n = 1..N (index 0 unused).  Returns the Lentz iteration count (diagnostic).
template <class Real, class C>
std::size_t downward_ratios(const Real& x, const C& m, std::size_t N, std::vector<Real>& p,
                            std::vector<C>& delta) {
  p.assign(N + 1, Real(0));
  delta.assign(N + 1, C(Real(0)));
  const C z = m * x;
  const C inv_z = recip(z);
  const Real inv_x = Real(1) / x;
  const C c = (m - C(Real(1))) * recip(m) * inv_x;  // (m−1)/(m x)

  LentzResult info_x, info_z;
  Real px = riccati_psi_ratio<Real, Real>(N, x, &info_x);
  C pz = riccati_psi_ratio<C, Real>(N, z, &info_z);
  // At the start Δ_N = P_N(mx) − P_N(x) − N c by direct subtraction: its error
  // (ε·|P|) is damped by the downward recurrence before n ≈ x matters.
  C d = (pz - C(px)) - c * Real(N);
  for (std::size_t n = N; n >= 2; --n) {
    avoid_zero<Real, Real>(px);
    avoid_zero<C, Real>(pz);
    p[n] = px;
    delta[n] = d;
    const Real rn = Real(n);
    const C inv_pz = recip(pz);
    const Real inv_px = Real(1) / px;
    const C nc = c * rn;
    d = (d - nc) * inv_pz * inv_px - nc;
    pz = inv_z * Real(2 * n - 1) - inv_pz;
    px = inv_x * Real(2 * n - 1) - inv_px;
  }
  avoid_zero<Real, Real>(px);
  p[1] = px;
  delta[1] = d;
  return info_x.iterations + info_z.iterations;
}

// cot z for Im z >= 0 without overflow: cot z = i(E+1)/(E−1), E = e^{2iz},
// |E| = e^{−2 Im z} <= 1.
template <class Real, class C>
C cot_upper(const C& z) {
  using std::cos;
  using std::exp;
  using std::sin;
  const Real r = exp(Real(-2) * z.imag());
  const C e(r * cos(Real(2) * z.real()), r * sin(Real(2) * z.real()));
  C den = e - C(Real(1));
  avoid_zero<C, Real>(den);
  const C q = (e + C(Real(1))) * recip(den);
  return C(-q.imag(), q.real());  // i·q
}

// Upward recurrence for Dₙ(z), one step at a time (used inside the series
// loop, so no storage).  Stable only where choose_method (series.hpp) allows.
template <class Real, class C>
struct UpwardLogDerivative {
  C inv_z;
  C d;  // D_n(z) for the current n
  explicit UpwardLogDerivative(const C& z) : inv_z(recip(z)), d(cot_upper<Real, C>(z)) {}
  const C& next(std::size_t n) {
    const C n_over_z = inv_z * Real(n);
    C den = n_over_z - d;
    avoid_zero<C, Real>(den);
    d = recip(den) - n_over_z;
    return d;
  }
};

}  // namespace attenuvis::mie::detail
