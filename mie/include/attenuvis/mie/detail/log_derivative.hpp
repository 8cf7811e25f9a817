// Logarithmic derivatives of Riccati–Bessel functions for the Mie series.
//
// Template detail of the Mie core: the recurrences of the series
// (mie/src/series.hpp, term_block.hpp), whose split constants the lanes of
// spheres() copy (sphere_lanes.cpp); tests and benchmarks run its start
// values and downward pass on their own.
//
// Notation (B&H ch. 4): ψₙ(z) = z jₙ(z), Dₙ(z) = ψₙ'(z)/ψₙ(z).  The core
// carries yₙ(z) = ψ_{n+1}(z)/ψₙ(z), which is small (≈ z/(2n+3)) for small z:
//     Dₙ(z) = (n+1)/z − yₙ(z)                                   (B&H 4.89)
//     yₙ(z) = 1 / ((2n+3)/z − y_{n+1}(z))                        (downward)
//     Dₙ(z) = 1/(n/z − D_{n-1}(z)) − n/z,   D₀(z) = cot z           (upward)
// Writing Dₙ through yₙ removes the leading (n+1)/z exactly, so
// m Dₙ(mx) − Dₙ(x) = −m yₙ(mx) + yₙ(x) is formed without the 1/x² cancellation
// that ruins bₙ at x = 1e-8 (trap small-x; the traps are listed in series.hpp).
//
// Trap m-near-1.  The numerators of aₙ, bₙ are O(m−1) and would be formed by
// cancellation.  We carry the difference δₙ = yₙ(mx) − yₙ(x) through its own
// downward recurrence, obtained by subtracting the two y recurrences:
//     δₙ = ((2n+3) c + δ_{n+1}) · yₙ(mx) · yₙ(x),   c = (m−1)/(m x),
// (since (2n+3)/x − (2n+3)/(mx) = (2n+3)c).  Every term is proportional to
// (m−1) explicitly, so nothing cancels; yₙ(mx) and yₙ(x) come from their own
// recurrences.  The start δ_N = y_N(mx) − y_N(x) has an error ε|y_N| that the
// factor Π yₖ(x) (≪ 1 above n ≈ x) damps long before it matters.
//
// Trap start-value.  Both recurrences start at the top index N from the
// exact values given by Lentz's continued fraction (lentz.hpp), or from 0 at
// N + K where miller_depth() proves the start forgotten by N (to ε/16);
// never from 0 at a guessed index.
// Trap large-kx.  Only ratios appear; nothing grows like e^{kx}.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/detail/complex_ops.hpp"
#include "attenuvis/mie/detail/lentz.hpp"
#include "attenuvis/mie/detail/scratch.hpp"

namespace attenuvis::mie::detail {

// Phase accuracy.  For x ~ 1e6 the recurrences are run through ~x steps of
// oscillation, and Qback (and, less, Qext) depend on the phase of ψₙ(mx) to
// within ~100× the phase error (resonance ripple).  Rounding 1/x or 1/(mx)
// once and reusing it shifts every coefficient (2n+1)/z the same way — a
// systematic phase error of |z|ε ≈ 1e-10, i.e. 1e-8 in Qback at x = 1e6.
// So the coefficients k/z are formed from 1/z carried in two parts (hi + lo,
// from extended precision), which makes their rounding errors independent
// from step to step; they then add up only like a random walk.
//
// k/z is wanted correctly rounded (measured: rounding k·hi first and then
// adding k·lo, two roundings, leaves 10-80× more error in Qback at x = 100,
// m = 10, and at x = 2041, m = 1.33).  std::fma would do it, but on a baseline
// x86-64 build it is a library call that spills every live register.  Instead
// hi is split into two halves of 26 significant bits (Veltkamp/Dekker): for an
// integer k < 2^26 (every index the core uses: k <= 2N + 3 with x <= 2e7)
// k·h₁ and k·h₂ are exact, and k/z = k·h₁ + (k·h₂ + k·lo) is rounded once up
// to the rounding of the small bracket, ~2^-26 ulp.
struct SplitInverse {
  double h1 = 0, h2 = 0, lo = 0;
  SplitInverse() = default;
  SplitInverse(double hi, double low) : lo(low) {
    const double t = hi * 134217729.0;  // 2^27 + 1
    h1 = t - (t - hi);
    h2 = hi - h1;
  }
  double operator()(double k) const { return k * h1 + (k * h2 + k * lo); }
};

template <class Real>
struct ScaledInverse {  // k/x for real x
  Real hi;
  SplitInverse split;  // double only
  explicit ScaledInverse(const Real& x) {
    if constexpr (std::is_same_v<Real, double>) {
      const long double inv = 1.0L / static_cast<long double>(x);
      hi = static_cast<double>(inv);
      split = SplitInverse(hi, static_cast<double>(inv - hi));
    } else {
      hi = Real(1) / x;
    }
  }
  Real operator()(const Real& k) const {
    if constexpr (std::is_same_v<Real, double>) return split(k);
    else return k * hi;
  }
};

template <class Real, class C>
struct ScaledInverseComplex {  // k/z for z = m x, formed without rounding m x first
  C hi;
  SplitInverse re, im;  // double only
  ScaledInverseComplex(const Real& x, const C& m) {
    if constexpr (std::is_same_v<Real, double>) {
      using LC = std::complex<long double>;
      const LC z = LC(m.real(), m.imag()) * static_cast<long double>(x);
      const long double n2 = z.real() * z.real() + z.imag() * z.imag();
      const LC inv(z.real() / n2, -z.imag() / n2);
      hi = C(static_cast<double>(inv.real()), static_cast<double>(inv.imag()));
      re = SplitInverse(hi.real(), static_cast<double>(inv.real() - hi.real()));
      im = SplitInverse(hi.imag(), static_cast<double>(inv.imag() - hi.imag()));
    } else {
      hi = recip(C(m * x));
    }
  }
  C operator()(const Real& k) const {
    if constexpr (std::is_same_v<Real, double>) return C(re(k), im(k));
    else return hi * k;
  }
};

// Replace an exact zero (a pole of the next step) by a tiny number.  Exact
// zeros are possible only by accident of rounding, but must not become inf.
template <class T, class Real>
inline void avoid_zero(T& v) {
  if (v == T(Real(0))) v = T((std::numeric_limits<Real>::min)() * Real(1e20));
}

// Depth K of the Miller start of downward_ratios (double; 0: Lentz start).
// Where a = max(x, |mx|) <= N/2, every yₖ(x), yₖ(mx) with k >= N, and every
// value of the recurrence yₖ = 1/((2k+3)/z − yₖ₊₁) started from 0 above it,
// is bounded by ρ = a/(2N + 3 − a) < 1/3 (induction: |yₖ₊₁| <= 1 gives
// |yₖ| <= 1/((2k+3)/|z| − 1)).  Since 1/u − 1/v = (v − u)/(u v), the error
// of the start value 0 at index N + K (at most ρ) reaches index N multiplied
// by Π|yₖ ŷₖ| <= ρ^{2K}; relative to |y_N| >= b/(2N + 3 + b), b = min(x, |mx|),
// it is below ε/16 once ρ^{2K+1} (2N + 3 + b)/b <= ε/16 — as good as the
// continued fraction's own stopping test (|Δ − 1| < ε, lentz.hpp).  The δ
// recurrence (trap m-near-1) starts from δ = 0 there and is damped alike.
// At x ≲ 10 a few steps (4 at x = 0.1) replace two continued fractions that
// cost a fifth of the call.  Deterministic in (x, m, N): spheres() computes
// the same K for each lane (sphere_lanes.cpp).
inline std::size_t miller_depth(double x, std::complex<double> m, std::size_t N) {
  const double az = std::sqrt(norm2(m)) * x;
  const double a = std::max(x, az), b = std::min(x, az);
  const double n = static_cast<double>(N);
  if (!(a <= 0.5 * n) || !(b > 0)) return 0;
  const double rho = a / (2 * n + 3 - a);
  const double tol = std::numeric_limits<double>::epsilon() / 16;
  double err = rho * ((2 * n + 3 + b) / b);
  std::size_t K = 0;
  while (err > tol && K < 64) err *= rho * rho, ++K;
  return err <= tol ? std::max<std::size_t>(K, 1) : 0;
}

// What the complex slot of the downward pass holds.
enum class Slot {
  difference,  // δₙ = yₙ(mx) − yₙ(x)   (|m−1| small: trap m-near-1)
  value,       // yₙ(mx)              (m far from 1: δ would only add rounding)
  none,        // nothing (Dₙ(mx) goes upward, or perfect conductor)
};

// ρₙ = ξ_{n-1}(x)/ξₙ(x) upward from ρ₀ = ξ₋₁/ξ₀ = i by 1/ρₙ = (2n−1)/x − ρ_{n-1}
// (stable: ξ is the dominant solution).  It runs in the same loop as the
// downward recurrences below: the chains are independent, so their division
// latencies overlap instead of adding up.
template <class Real, class C>
struct HankelRatio {
  C rho{Real(0), Real(1)};
  template <class OverX>
  const C& next(std::size_t n, const OverX& over_x) {
    rho = recip(C(over_x(index_real<Real>(2 * n - 1))) - rho);
    return rho;
  }
};

// Downward pass from index N: fills y[n] = yₙ(x) for n = 0..N, rho[n] = ρₙ
// for n = 1..N and, according to `slot`, w[n] = δₙ or yₙ(mx).
// W is the stored complex type: it may be narrower than C (see SlotStore
// below), since each wₙ is used once and not fed into a product.
//
// In Slot::difference mode, entry n holds δₙ only where yₙ(mx) = yₙ(x) + δₙ
// does not cancel (|yₙ(mx)| >= |yₙ(x)|/8); near a pole of yₙ(x) (ψₙ(x) ≈ 0)
// that m does not share, it holds yₙ(mx) itself and is_value[n] = 1.  Without
// this, a single term near such a pole loses ε|yₙ(x)/yₙ(mx)| (1e-8 at
// x = 116.78455902863854, m = 1.33+1e-5i, i.e. 9e-9 in Qback).
//
// Start values: Lentz's continued fractions at index N + 1, or — with
// miller > 0 (see miller_depth) — the same recurrences run from yₙ = 0 at
// index N + miller down to N, which gives yₙ(x), yₙ(mx) and δₙ to within
// ε/16 of their values at a fraction of the cost.
template <class Real, class C, class YArray, class RhoArray, class WArray, class FlagArray>
void downward_ratios(const ScaledInverse<Real>& over_x_in, const ScaledInverseComplex<Real, C>& over_z_in,
                     const C& m, std::size_t N, Slot slot, YArray& y_buf, RhoArray& rho_buf, WArray& w_buf,
                     FlagArray& is_value_buf, std::size_t miller = 0) {
  // Every entry is written below before it is read.
  is_value_buf.resize(slot == Slot::difference ? N + 1 : 0);
  y_buf.resize(N + 1);
  rho_buf.resize(N + 2);
  w_buf.resize(slot == Slot::none ? 0 : N + 1);
  // Locals and raw pointers: the flag stores (unsigned char, which may alias
  // anything) otherwise force the buffer pointers and the split constants of
  // k/x, k/(mx) to be reloaded from memory at every order.
  const ScaledInverse<Real> over_x = over_x_in;
  const ScaledInverseComplex<Real, C> over_z = over_z_in;
  auto* const y = &y_buf[0];
  auto* const rho = &rho_buf[0];
  auto* const w = slot == Slot::none ? nullptr : &w_buf[0];
  auto* const is_value = slot == Slot::difference ? &is_value_buf[0] : nullptr;
  HankelRatio<Real, C> hankel;
  if (slot == Slot::none) {
    // y_N = ψ_{N+1}/ψ_N = 1/(ψ_N/ψ_{N+1}).
    Real yx = Real(1) / riccati_psi_ratio<Real, Real>(N + 1, over_x);
    for (std::size_t n = N;; --n) {
      y[n] = yx;
      store(rho[N + 1 - n], hankel.next(N + 1 - n, over_x));
      if (n == 0) break;
      Real den = over_x(index_real<Real>(2 * n + 1)) - yx;
      avoid_zero<Real, Real>(den);
      yx = Real(1) / den;
    }
    return;
  }
  const C c = (m - C(Real(1))) * over_z(Real(1));  // (m−1)/(m x)
  Real yx;
  C yz, d;
  // One step down from index n to n − 1 of the three ratios (k = 2n + 1);
  // δ only when asked (Slot::value never reads it).
  const auto step_down = [&](std::size_t n, bool with_delta) {
    const Real k = index_real<Real>(2 * n + 1);
    Real den_x = over_x(k) - yx;
    C den_z = over_z(k) - yz;
    avoid_zero<Real, Real>(den_x);
    avoid_zero<C, Real>(den_z);
    yx = Real(1) / den_x;
    yz = recip(den_z);
    if (with_delta) d = cmul(C(c * k + d), yz) * yx;
  };
  if (miller > 0) {
    // The loop below without its stores, from zeros at index N + miller
    // (δ only where the slot holds it, as below).
    yx = Real(0), yz = C(Real(0)), d = C(Real(0));
    for (std::size_t n = N + miller; n > N; --n) step_down(n, slot == Slot::difference);
  } else {
    yx = Real(1) / riccati_psi_ratio<Real, Real>(N + 1, over_x);  // ψ_{N+1}/ψ_N
    yz = recip(riccati_psi_ratio<C, Real>(N + 1, over_z));
    d = yz - C(yx);
  }
  for (std::size_t n = N;; --n) {
    y[n] = yx;
    store(rho[N + 1 - n], hankel.next(N + 1 - n, over_x));
    if (slot == Slot::difference) {
      const bool value = 64 * norm2(yz) < yx * yx;
      is_value[n] = value;
      const C& v = value ? yz : d;
      store(w[n], v);
    } else {
      store(w[n], yz);
    }
    if (n == 0) break;
    step_down(n, slot == Slot::difference);
  }
}

// Storage of the per-term complex slot of the downward pass (w below): a
// trivial pair of doubles for the double product, also where its recurrences
// run in long double (use_extended(), mie/src/sphere_checks.hpp) — 16 instead
// of 32 bytes per term, and each entry is used once.
template <class Real>
struct SlotStore {
  using type = Complex<Real>;
};
template <>
struct SlotStore<long double> {
  using type = StoredComplex<double>;
};
template <>
struct SlotStore<double> {
  using type = StoredComplex<double>;
};

// The tables downward_ratios fills, per thread and reused between calls
// (sum_series, mie/src/series.hpp): a fresh ~33·N-byte allocation per call
// costs more in page faults than the series itself for x ≳ 1e4.  Tables above
// 8 MB (x ≳ 2.5e5) are given back after each call so a single x = 1e6 call
// does not pin 33 MB per thread (see scratch.hpp).
template <class Work>
struct DownwardTables {
  Scratch<Work> y;
  Scratch<StoredComplex<Work>> rho;
  Scratch<typename SlotStore<Work>::type> w;
  Scratch<unsigned char> is_value;
  void release_large() {
    constexpr std::size_t kKeep = std::size_t(8) << 20;
    if (y.capacity_bytes() > kKeep) y.release();
    if (rho.capacity_bytes() > kKeep) rho.release();
    if (is_value.capacity_bytes() > kKeep) is_value.release();
    if (w.capacity_bytes() > kKeep) w.release();
  }
};

// cot z for Im z >= 0 without overflow: cot z = i(E+1)/(E−1), E = e^{2iz},
// |E| = e^{−2 Im z} <= 1.
template <class Real, class C>
C cot_upper_plain(const C& z) {
  using std::cos;
  using std::exp;
  using std::sin;
  if (z.imag() == 0) return C(cos(z.real()) / sin(z.real()), Real(0));  // real: keep Im D exactly 0
  const Real r = exp(Real(-2) * z.imag());
  const C e(r * cos(Real(2) * z.real()), r * sin(Real(2) * z.real()));
  C den = e - C(Real(1));
  avoid_zero<C, Real>(den);
  const C q = (e + C(Real(1))) * recip(den);
  return C(-q.imag(), q.real());  // i·q
}

// cot(m x) without rounding m x first (phase accuracy, see ScaledInverse).
template <class Real, class C>
C cot_upper(const Real& x, const C& m) {
  if constexpr (std::is_same_v<Real, double>) {
    using LC = std::complex<long double>;
    const LC z = LC(m.real(), m.imag()) * static_cast<long double>(x);
    const LC v = cot_upper_plain<long double, LC>(z);
    return C(static_cast<double>(v.real()), static_cast<double>(v.imag()));
  } else {
    return cot_upper_plain<Real, C>(C(m * x));
  }
}

// Upward recurrence for Dₙ(z), one step at a time (used inside the series
// loop, so no storage).  Stable only where choose_method (series.hpp) allows.
template <class Real, class C>
struct UpwardLogDerivative {
  ScaledInverseComplex<Real, C> over_z;
  C d;  // D_n(z) for the current n
  // active = false: an unused placeholder (skips the cot evaluation).
  UpwardLogDerivative(const Real& x, const C& m, const ScaledInverseComplex<Real, C>& over, bool active)
      : over_z(over), d(active ? cot_upper<Real, C>(x, m) : C(Real(0))) {}
  const C& next(std::size_t n) {
    const C n_over_z = over_z(index_real<Real>(n));
    C den = n_over_z - d;
    avoid_zero<C, Real>(den);
    d = recip(den) - n_over_z;
    return d;
  }
};

}  // namespace attenuvis::mie::detail
