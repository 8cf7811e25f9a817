// The Mie series for a homogeneous sphere, templated on the floating type.
//
// Private to the library: instantiated by sphere_double.cpp (Real = double)
// and sphere_referee.cpp (Real = 50-digit); sphere_lanes.cpp takes its
// choose_method() and riccati_psi1(), so that the lanes of spheres() decide
// and start as sphere() does.  What weather/, apps/ and python/ include
// (attenuvis/mie.hpp and its siblings) stays free of these templates.
//
// Method (B&H ch. 4 rewritten in ratios, cf. Wiscombe 1979 NCAR/TN-140+STR §3):
//   aₙ = Rₙ (Dₙ(mx)/m − Dₙ(x)) / (Dₙ(mx)/m − Gₙ(x))
//   bₙ = Rₙ (m Dₙ(mx) − Dₙ(x)) / (m Dₙ(mx) − Gₙ(x))
// with Rₙ = ψₙ(x)/ξₙ(x), Gₙ = ξₙ'/ξₙ.  This follows from B&H 4.88 after
// dividing by ψₙ (numerator) and ξₙ (denominator) and using ψ_{n-1}/ψₙ =
// Dₙ + n/x, ξ_{n-1}/ξₙ = Gₙ + n/x.
//   * Real argument (trap small-x): ψₙ(x) enters only through Pₙ(x) =
//     ψ_{n-1}/ψₙ from the downward recurrence (Lentz start), and ξₙ through
//     ρₙ = ξ_{n-1}/ξₙ from 1/ρₙ = (2n−1)/x − ρ_{n-1}, ρ₀ = ξ₋₁/ξ₀ = i (upward,
//     stable since ξ is the dominant solution).  Rₙ = R_{n-1} ρₙ/Pₙ with
//     R₁ = ρ₁ ψ₁/ξ₀, 1/ξ₀ = sin x + i cos x, ψ₁ = ψ₀ y₀ (riccati_psi1, trap
//     sin-zero).  No ψ₁ = sin x/x − cos x anywhere, and Gₙ + n/x = ρₙ is
//     never formed by subtraction.
//   * Absorption (trap weak-absorption): Re aₙ − |aₙ|² = −Im(T) / (|ξₙ|²
//     |T − Gₙ|²) with T = Dₙ(mx)/m (bₙ: T = m Dₙ(mx)), from the Wronskian
//     ψₙ'χₙ − ψₙχₙ' = 1.  Summing this gives Qabs to full relative accuracy
//     even when Qabs ≪ Qsca, where Qext − Qsca would cancel.  1/|ξₙ|² =
//     Π|ρ_k|² (|ξ₀| = 1) is carried as a product, so it underflows harmlessly
//     instead of overflowing.
//   * Dₙ(mx): downward from a Lentz or Miller start (log_derivative.hpp, with
//     the δ difference for trap m-near-1), or — when the continued fraction would
//     need far more steps than the series has terms and the upward recurrence
//     is provably stable — upward from cot(mx); see choose_method().
//   * Sums are compensated (Kahan) so that 1e6 terms of alternating sign
//     (Qback, g) keep their digits.
//
// The Mie traps: numerical pitfalls, each seen in widely used Mie codes, that
// this core is built to avoid.  Comments and tests refer to them by name
// ("trap m-near-1"); tests/mie/test_mie_traps.cpp tests truncation,
// start-value, small-x, sin-zero, m-near-1, psi-zero and large-kx against the
// 50-digit referee, tests/mie/test_mie_referee.cpp back-cancellation.
//   truncation          Stopping at Wiscombe's N = x + 4.05 x^{1/3} + 2 leaves
//                       ~1e-10 in Qext and up to ~1e-5 in Qback; the series is
//                       summed until the terms stop changing the sums.
//   start-value         Dₙ(mx) downward from an arbitrary start (0 at
//                       max(N, |mx|) + 15) is not forgotten for large, weakly
//                       absorbing spheres; every downward recurrence starts
//                       from Lentz's continued fraction (lentz.hpp), or from
//                       0 only as far above N as miller_depth() proves enough
//                       (log_derivative.hpp).
//   upward-instability  Dₙ(mx) upward from cot(mx) amplifies rounding errors by
//                       ~exp(N² Im z/|z|²) and is unstable for n > |z|; it is
//                       used only where choose_method() proves it stable.
//   small-x             ψ₁(x) = sin x/x − cos x and the leading 1/x terms of
//                       m Dₙ(mx) − Dₙ(x) cancel catastrophically for x ≪ 1
//                       (negative Qext below x ≈ 3e-3 in one code); only
//                       ratios yₙ = ψₙ₊₁/ψₙ appear, with (n+1)/x removed exactly.
//   sin-zero            Rₙ = ψₙ/ξₙ as the product ψ₀/ξ₀ · Π ρₖ yₖ₋₁ divides
//                       by ψ₀ = sin x through y₀ = ψ₁/ψ₀; at x ≈ jπ (x =
//                       182.21237390820801 = 58π to 2.5e-18 in sin x) y₀ comes
//                       from 3/x − y₁ formed by cancellation, exactly 0 in
//                       double there, and every Rₙ is wrong: NaN Qext there,
//                       Qext 2.203 for 2.134 at x = 94.24777960769377 (sin x
//                       = −2.5e-14), 5.04 for 3.92 at x = 6.283185307179585.
//                       Poles of yₖ with k >= 1 are
//                       harmless (yₖ₋₁ yₖ is accurate); ψ₁ is formed without
//                       sin x where it is small (riccati_psi1).
//   m-near-1            The numerators of aₙ, bₙ and m² − 1 are O(m − 1) and
//                       cancel as m → 1; the difference δₙ = yₙ(mx) − yₙ(x)
//                       has its own recurrence (log_derivative.hpp).
//   psi-zero            Near a zero of ψₙ(x) the ratio ψₙ₊₁/ψₙ is formed by
//                       cancellation and yₙ(mx) − yₙ(x) loses digits; such
//                       entries are stored as values, and the recurrences run
//                       in extended precision (see Options::precision).
//   large-kx            ψₙ(mx) ~ e^{kx} overflows for large k x unless only
//                       ratios appear (they do everywhere here).
//   weak-absorption     Qabs = Qext − Qsca loses all digits when Qabs ≪ Qsca;
//                       Qabs is a sum of its own, from the Wronskian.
//   back-cancellation   Qback is an alternating sum that cancels by ~x, so it
//                       amplifies the accumulated rounding of the recurrences
//                       (and the phase error of k/z, see ScaledInverse).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/detail/log_derivative.hpp"
#include "attenuvis/mie/detail/scratch.hpp"
#include "attenuvis/mie/detail/term_count.hpp"
#include "angular_sums.hpp"
#include "term_block.hpp"

namespace attenuvis::mie::detail {

template <class Real>
struct KahanSum {
  Real sum{0}, carry{0};
  void add(const Real& v) {
    const Real y = v - carry;
    const Real t = sum + y;
    carry = (t - sum) - y;
    sum = t;
  }
  Real value() const { return sum - carry; }
};

enum class DMethod { downward, upward };

// Dₙ(mx) for n <= N: the Lentz continued fraction at index N needs about
// |mx| − N steps when |mx| > N (oscillatory region), fewer when Im(mx) is
// large: the downward map contracts by about exp(−2n Im z/|z|²) per step, so
// K steps beyond N damp by exp(−(K² + 2NK) Im z/|z|²).  The upward
// recurrence amplifies errors by exp(E), E = N² Im z/|z|² (Kattawar & Plass
// 1967; Wiscombe 1979 §3.b), and is unstable for n > |z|.  We go upward only
// when the continued fraction would cost more than N/2 + 1000 steps, N < |z|
// by that margin, and E <= 3 (error growth < 20 ε).  Otherwise the fraction
// costs at most N(√(1+L/3) − 1) < 3N steps (double) — bounded either way.
template <class Real, class C>
DMethod choose_method(double x, std::complex<double> m, std::size_t N) {
  const std::complex<double> z = m * x;
  const double az = std::sqrt(norm2(z));
  const double n = static_cast<double>(N);
  if (az <= n) return DMethod::downward;
  const double b = z.imag();
  const double E = n * n * b / (az * az);
  const double L = tail_log_tolerance<Real>();
  double k = az - n;
  if (E > 0) k = std::min(k, n * (std::sqrt(1.0 + L / E) - 1.0));
  if (k <= 0.5 * n + 1000.0) return DMethod::downward;
  return E <= 3.0 ? DMethod::upward : DMethod::downward;
}

// The per-block term loops: the run-time dispatched clones for double
// (term_block_double.cpp), the templates otherwise.
template <class Real>
void block_terms(bool pec, const TermConstants<Real>& k, const TermInputs<Real>& in, std::size_t count,
                 const Complex<Real>& a_prev, const Complex<Real>& b_prev, TermOutputs<Real>& out) {
  if constexpr (std::is_same_v<Real, double>) {
    if (pec) conductor_terms_double(k, in, count, out);
    else sphere_terms_double(k, in, count, out);
    sum_terms_double(in, count, a_prev, b_prev, out);
  } else {
    if (pec) conductor_terms(k, in, count, out);
    else sphere_terms(k, in, count, out);
    sum_terms(in, count, a_prev, b_prev, out);
  }
}

// The compensated sums of the series, one per SumLane (term_block.hpp), and
// what is read from them.
template <class Real>
struct SeriesSums {
  KahanSum<Real> lane[SumLane::count];
  // Order n's terms (entry i of a block).
  void add(const TermOutputs<Real>& t, std::size_t i, std::size_t n) {
    lane[SumLane::ext].add(t.ext[i]);
    lane[SumLane::sca].add(t.sca[i]);
    lane[SumLane::abs].add(t.abs[i]);
    lane[SumLane::back_re].add(t.back_re[i]);
    lane[SumLane::back_im].add(t.back_im[i]);
    // g (B&H 4.74): Σ n(n+2)/(n+1) Re(aₙa*ₙ₊₁ + bₙb*ₙ₊₁) + Σ (2n+1)/(n(n+1)) Re(aₙb*ₙ),
    // with k(k+2)/(k+1) = n − 1/n for k = n − 1 and (2n+1)/(n(n+1)) = 1/n + 1/(n+1).
    // Two sums, so that neither compensated chain waits for the other.
    if (n >= 2) lane[SumLane::g_cross].add(t.g_cross[i]);
    lane[SumLane::g_self].add(t.g_self[i]);
  }
  // Whether order n (entry i of a block, just added) is the last one.
  bool converged(const TermOutputs<Real>& t, std::size_t i, std::size_t n, double x, const Real& tol) const {
    return series_converged(n, x, t.size[i], tol, lane[SumLane::ext].sum, lane[SumLane::back_re].sum,
                            lane[SumLane::back_im].sum);
  }
  void finish(const Real& x, bool pec, std::size_t terms, Efficiencies<Real>& q) const {
    const Real inv_x = Real(1) / x;
    const Real f = Real(2) * inv_x * inv_x;
    q.terms = terms;
    const Real br = lane[SumLane::back_re].value(), bi = lane[SumLane::back_im].value();
    const Real ssum = lane[SumLane::sca].value();
    q.qext = f * lane[SumLane::ext].value();
    q.qsca = f * ssum;
    q.qabs = pec ? Real(0) : f * lane[SumLane::abs].value();
    q.qback = (br * br + bi * bi) * inv_x * inv_x;
    q.g = ssum > 0 ? Real(2) * (lane[SumLane::g_cross].value() + lane[SumLane::g_self].value()) / ssum : Real(0);
    q.qpr = q.qext - q.g * q.qsca;
  }
};

// SeriesSums<double> from the vector form of sum_block_double, lane by lane.
inline void VectorSums::to(SeriesSums<double>& s) const {
  for (int c = 0; c < SumLane::count; ++c) s.lane[c].sum = sum[c], s.lane[c].carry = carry[c];
}

// ψ₁(x) = ψ₀ y₀ from y₀ = ψ₁/ψ₀ of the downward pass, without the small-x
// cancellation of sin x/x − cos x and without dividing by ψ₀ = sin x where it
// is small (trap sin-zero).  At x ≈ jπ the recurrence forms 1/y₀ = 3/x − y₁ =
// ψ₀/ψ₁ by cancellation, so y₀ carries a relative error ~ε(3/x)|ψ₁/ψ₀| (or is
// the avoid_zero() stand-in 1/tiny when the difference is exactly zero), and
// ψ₀·y₀ = sin x · y₀ inherits it.  There we go one order further down:
// ψ₁ = ψ₋₁ y₋₁ y₀ with ψ₋₁ = cos x and y₋₁ = ψ₀/ψ₋₁ = 1/(1/x − y₀), i.e.
// ψ₁ = cos x · y₀/(1/x − y₀), whose sensitivity to the error of y₀ is
// |(1/x)/(1/x − y₀)| = |tan x|/x < 1 when |sin x| < |cos x|.  (Errors of y₀ in
// the other branch are ~ε(3/x + |y₁|)|ψ₁|/|sin x| with |sin x| >= 1/√2.)
template <class Work>
Work riccati_psi1(const Work& sx, const Work& cx, const Work& y0, const Work& inv_x) {
  using std::abs;
  if (abs(sx) >= abs(cx)) return sx * y0;
  return cx * (y0 / (inv_x - y0));
}

// Pass 1 of a block (serial, working precision): Rₙ = R_{n-1} ρₙ ψₙ/ψ_{n-1},
// sₙ = 1/|ξₙ|², and each order's inputs for term_block.hpp.
// The mode (perfect conductor, or the slot) is a template argument, so that
// the per-order loop carries no test of it.
template <class Real, class Work, bool pec, Slot slot, class Tables>
void block_inputs_for(std::size_t first, std::size_t count, const Tables& tables,
                      const ScaledInverseComplex<Work, Complex<Work>>& over_mxw,
                      UpwardLogDerivative<Work, Complex<Work>>& upward, Complex<Work>& R_io, Work& s_io,
                      TermInputs<Real>& in) {
  using C = Complex<Real>;
  using CW = Complex<Work>;
  const auto& y = tables.y;
  const auto& w = tables.w;
  // The running products in locals: through the references, every store into
  // `in` (doubles, which might alias them) forced a reload.
  CW R_w = R_io;
  Work s_w = s_io;
  Real sign = first % 2 == 0 ? Real(1) : Real(-1);  // (−1)ⁿ
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t n = first + i;
    const CW rho_w(tables.rho[n].real(), tables.rho[n].imag());  // ρₙ = ξ_{n-1}/ξₙ
    // R₁ = (ψ₁/ξ₀) ρ₁ with ψ₁/ξ₀ given as R_w (trap sin-zero: no y₀ here).
    R_w = n == 1 ? cmul(R_w, rho_w) : cmul(R_w, rho_w) * y[n - 1];
    s_w *= norm2(rho_w);
    const Real yx = static_cast<Real>(y[n]);
    in.rn[i] = index_real<Real>(n);
    in.yx[i] = yx;
    in.R_re[i] = static_cast<Real>(R_w.real()), in.R_im[i] = static_cast<Real>(R_w.imag());
    in.s[i] = static_cast<Real>(s_w);
    in.rho_re[i] = static_cast<Real>(rho_w.real()), in.rho_im[i] = static_cast<Real>(rho_w.imag());
    in.sign[i] = sign;
    sign = -sign;
    if constexpr (pec) continue;
    if (slot == Slot::difference && !tables.is_value[n]) {
      const C dy(w[n].real(), w[n].imag());
      const C ymx = C(yx) + dy;
      in.dy_re[i] = dy.real(), in.dy_im[i] = dy.imag();
      in.ymx_re[i] = ymx.real(), in.ymx_im[i] = ymx.imag();
      in.difference[i] = Real(1);
    } else {
      C ymx;
      if constexpr (slot != Slot::none) {
        ymx = C(w[n].real(), w[n].imag());
      } else {
        const CW v = over_mxw(index_real<Work>(n + 1)) - upward.next(n);
        ymx = C(static_cast<Real>(v.real()), static_cast<Real>(v.imag()));
      }
      in.ymx_re[i] = ymx.real(), in.ymx_im[i] = ymx.imag();
      in.dy_re[i] = Real(0), in.dy_im[i] = Real(0);
      in.difference[i] = Real(0);
    }
  }
  R_io = R_w;
  s_io = s_w;
}

template <class Real, class Work, class Tables>
void block_inputs(std::size_t first, std::size_t count, const Tables& tables, bool pec, Slot slot,
                  const ScaledInverseComplex<Work, Complex<Work>>& over_mxw,
                  UpwardLogDerivative<Work, Complex<Work>>& upward, Complex<Work>& R_w, Work& s_w,
                  TermInputs<Real>& in) {
  if (pec)
    block_inputs_for<Real, Work, true, Slot::none>(first, count, tables, over_mxw, upward, R_w, s_w, in);
  else if (slot == Slot::difference)
    block_inputs_for<Real, Work, false, Slot::difference>(first, count, tables, over_mxw, upward, R_w, s_w, in);
  else if (slot == Slot::value)
    block_inputs_for<Real, Work, false, Slot::value>(first, count, tables, over_mxw, upward, R_w, s_w, in);
  else
    block_inputs_for<Real, Work, false, Slot::none>(first, count, tables, over_mxw, upward, R_w, s_w, in);
}

// The downward pass over the tables of N + 1 entries (log_derivative.hpp),
// from Lentz's start or, where miller_depth() allows it (Work = double, a
// complex slot), the cheaper Miller start.
template <class Real, class Work>
void fill_downward_tables(const Real& x, const Complex<Real>& m, std::size_t N, Slot slot,
                          const ScaledInverse<Work>& over_xw, const ScaledInverseComplex<Work, Complex<Work>>& over_mxw,
                          const Complex<Work>& mw, DownwardTables<Work>& tables) {
  std::size_t miller = 0;
  if constexpr (std::is_same_v<Work, double>) {
    if (slot != Slot::none)
      miller = miller_depth(static_cast<double>(x), std::complex<double>(m.real(), m.imag()), N);
  }
  downward_ratios<Work, Complex<Work>>(over_xw, over_mxw, mw, N, slot, tables.y, tables.rho, tables.w,
                                       tables.is_value, miller);
}

// The constants of the term formulas; k/x and k/(mx) are those of the
// recurrences when Real is Work.
template <class Real, class Work>
TermConstants<Real> term_constants(const Real& x, const Complex<Real>& m, const ScaledInverse<Work>& over_xw,
                                   const ScaledInverseComplex<Work, Complex<Work>>& over_mxw) {
  using C = Complex<Real>;
  const C m_minus_1 = m - C(Real(1));
  const C m2_minus_1_over_m = m_minus_1 * (m + C(Real(1))) * recip(m);  // (m²−1)/m, trap m-near-1
  const C m2_minus_1 = m_minus_1 * (m + C(Real(1)));
  return {m.real(), m.imag(), m_minus_1.real(), m_minus_1.imag(), m2_minus_1_over_m.real(), m2_minus_1_over_m.imag(),
          m2_minus_1.real(), m2_minus_1.imag(),
          [&] {
            if constexpr (std::is_same_v<Real, Work>) return over_xw;
            else return ScaledInverse<Real>(x);
          }(),
          [&] {
            if constexpr (std::is_same_v<Real, Work>) return over_mxw;
            else return ScaledInverseComplex<Real, C>(x, m);
          }()};
}

// The relative size of the last term kept (the converged rule), once per type.
template <class Real>
Real series_tolerance() {
  static const double tol = std::exp(-tail_log_tolerance<Real>());
  return Real(tol);
}

// What pass 3 did with a block: how many of its orders it summed, and whether
// the last of them ended the series (the converged rule).
struct BlockSum {
  std::size_t used;
  bool stopped;
};

// Pass 3 of a block (serial): the compensated sums and the convergence test.
// In double the seven sums advance together, two 4-wide vector operations per
// order (sum_block_double, the same operations per sum as SeriesSums::add).
template <class Real>
BlockSum sum_block(const TermOutputs<Real>& terms, std::size_t first, std::size_t count, double x,
                   const Real& tol, bool converged_rule, SeriesSums<Real>& sums, VectorSums& vector_sums) {
  if constexpr (std::is_same_v<Real, double>) {
    const std::size_t used = sum_block_double(terms, first, count, x, tol, converged_rule, vector_sums);
    return {used, vector_sums.converged};
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t n = first + i;
      sums.add(terms, i, n);
      if (converged_rule && sums.converged(terms, i, n, x, tol)) return {i + 1, true};
    }
    return {count, false};
  }
}

// The extras of the orders first .. first + used − 1 that were summed.
template <class Real>
void add_extras(const Extras& extras, std::size_t first, std::size_t used, const TermOutputs<Real>& terms,
                std::optional<AngularSums<Real>>& angular, Scattering<Real>& out) {
  if (extras.coefficients) {
    for (std::size_t i = 0; i < used; ++i) {
      out.a.emplace_back(terms.a_re[i], terms.a_im[i]);
      out.b.emplace_back(terms.b_re[i], terms.b_im[i]);
    }
  }
  if (angular) angular->add_block(first, used, terms);
}

// One summation of the series from tables of N + 1 entries into `out`.
// Returns false if the converged rule asked for more than N terms.
// Blocks of kTermBlock orders go through the three passes of term_block.hpp.
template <class Real, class Work>
bool sum_series(const Real& x, const Complex<Real>& m, bool pec, const Extras& extras, bool converged_rule,
                std::size_t N, DMethod method, Slot slot, Scattering<Real>& out) {
  using C = Complex<Real>;
  using CW = Complex<Work>;
  using std::cos;
  using std::sin;
  const Work xw = static_cast<Work>(x);
  const CW mw(static_cast<Work>(m.real()), static_cast<Work>(m.imag()));
  const double xd = static_cast<double>(x);

  // yₙ(x), ρₙ and, in w, δₙ or yₙ(mx) (log_derivative.hpp).
  thread_local DownwardTables<Work> tables;
  struct Release {
    DownwardTables<Work>& t;
    ~Release() { t.release_large(); }
  } release_large_tables{tables};
  const ScaledInverse<Work> over_xw(xw);
  const ScaledInverseComplex<Work, CW> over_mxw(xw, mw);
  fill_downward_tables<Real, Work>(x, m, N, slot, over_xw, over_mxw, mw, tables);
  UpwardLogDerivative<Work, CW> upward(xw, mw, over_mxw, method == DMethod::upward);

  out = Scattering<Real>{};
  // Two tests of any_angle, not one block: with the copy and the emplace
  // together GCC cleared the optional's 184 bytes on every call (1.5% at x = 1).
  const bool any_angle = !extras.angles_deg.empty();
  if (any_angle) out.angles_deg = extras.angles_deg;  // the copy of an empty vector was ~1% of a call at x = 0.1
  std::optional<AngularSums<Real>> angular;
  if (any_angle) angular.emplace(extras.angles_deg, out);
  const TermConstants<Real> constants = term_constants<Real, Work>(x, m, over_xw, over_mxw);
  const Real tol = series_tolerance<Real>();
  SeriesSums<Real> sums;
  VectorSums vector_sums;  // double (pass 3)
  const Work sx = sin(xw), cx = cos(xw);
  const Work psi1 = riccati_psi1(sx, cx, tables.y[0], over_xw(Work(1)));
  CW R_w(sx * psi1, cx * psi1);  // ψ₁/ξ₀ (1/ξ₀ = sin x + i cos x); R₁ = ρ₁ ψ₁/ξ₀
  Work s_w(1);               // 1/|ξ₀|²
  C a_prev(Real(0)), b_prev(Real(0));
  thread_local TermInputs<Real> in;
  thread_local TermOutputs<Real> terms;
  bool converged = !converged_rule, stopped = false;
  std::size_t n_last = N;
  // The first block is short: at x ≲ 1 the series stops after 7–13 orders,
  // often well before the end of the first table, and the orders beyond the
  // stop would be computed for nothing.
  std::size_t block = kFirstTermBlock;
  for (std::size_t first = 1, count = 0; first <= N && !stopped; first += count, block = kTermBlock) {
    count = std::min(block, N + 1 - first);
    // Pass 1 (serial, working precision).
    block_inputs<Real, Work>(first, count, tables, pec, slot, over_mxw, upward, R_w, s_w, in);
    // Pass 2 (every order independently): aₙ, bₙ and their terms.  The count
    // is padded to a multiple of 4 (the clones' vector width in doubles) with
    // copies of the last order, so that a short block (small x) runs in
    // vector lanes too instead of a scalar remainder loop; the padded entries
    // are not summed.  (Multiples of 8 measured 4% slower at x = 0.1 and 1.)
    const std::size_t padded = std::min(kTermBlock, (count + 3) / 4 * 4);
    for (std::size_t i = count; i < padded; ++i) in.copy_entry(count - 1, i);
    block_terms<Real>(pec, constants, in, padded, a_prev, b_prev, terms);
    // Pass 3 (serial).
    const BlockSum summed = sum_block<Real>(terms, first, count, xd, tol, converged_rule, sums, vector_sums);
    if (summed.stopped) {  // at order first + used − 1
      converged = stopped = true;
      n_last = first + summed.used - 1;
    }
    add_extras(extras, first, summed.used, terms, angular, out);
    a_prev = C(terms.a_re[count - 1], terms.a_im[count - 1]);
    b_prev = C(terms.b_re[count - 1], terms.b_im[count - 1]);
  }
  if constexpr (std::is_same_v<Real, double>) vector_sums.to(sums);
  if (any_angle) angular->finish();
  sums.finish(x, pec, n_last, out.q);
  return converged;
}

// The series.  pec: perfectly conducting sphere (m ignored).
// Work: the type of the recurrences that run over all n (yₙ(x), yₙ(mx), δₙ,
// ρₙ, Rₙ, 1/|ξₙ|², upward Dₙ), whose rounding errors accumulate like √N·ε;
// Real: the type of each term's own arithmetic (aₙ, bₙ, sums), whose errors do
// not accumulate.  The double product chooses Work per call (see
// Options::precision in mie.hpp and use_extended() in sphere_checks.hpp).
//
// The converged rule first fills tables of first_terms(x) entries; in the
// rare case the series has not converged by then, it is summed again from
// tables of max_terms(x) entries (the previous bound, where it stops in any
// case).
template <class Real, class Work = Real>
Scattering<Real> mie_series(const Real& x, const Complex<Real>& m, bool pec, const Extras& extras,
                            const Options& options) {
  const double xd = static_cast<double>(x);
  const std::complex<double> md(static_cast<double>(m.real()), static_cast<double>(m.imag()));
  const bool converged_rule = options.terms == TermRule::converged;
  const double cbrt_x = bound_cbrt(xd);
  const std::size_t n_max =
      converged_rule ? max_terms<Real>(xd, cbrt_x) : std::max<std::size_t>(1, wiscombe_term_count(xd));
  // Dₙ(mx) upward or downward: decided for the longest table, so that the
  // choice does not depend on the first guess.
  const DMethod method = pec ? DMethod::downward : choose_method<Real, Complex<Real>>(xd, md, n_max);
  Slot slot = Slot::none;
  if (!pec && method == DMethod::downward) {
    const std::complex<double> d = md - 1.0;
    slot = norm2(d) < 0.25 ? Slot::difference : Slot::value;
  }
  Scattering<Real> out;
  std::size_t N = converged_rule ? first_terms<Real>(xd, cbrt_x) : n_max;
  while (!sum_series<Real, Work>(x, m, pec, extras, converged_rule, N, method, slot, out) && N < n_max)
    N = n_max;
  return out;
}

}  // namespace attenuvis::mie::detail
