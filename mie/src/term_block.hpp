// The Mie coefficients aₙ, bₙ and their contributions to the sums, for a
// block of consecutive orders n at once (template implementation detail of
// series.hpp).
//
// The series is evaluated in three passes per block of kTermBlock orders:
//   1. serial, in the working precision: the running products Rₙ = ψₙ/ξₙ and
//      sₙ = 1/|ξₙ|², and the inputs of each order (series.hpp);
//   2. here: every order independently — no value flows from n to n+1 — so
//      the loops are plain arithmetic on arrays that the compiler vectorises
//      (two lanes with SSE2; four or eight where the CPU has AVX2 or AVX-512,
//      chosen at run time: term_block_double.cpp);
//   3. serial: the compensated sums (series.hpp) and the convergence test
//      (series_converged below).
// The formulas are those of series.hpp's header (B&H 4.88 in ratios), written
// out in real and imaginary parts, in the same order of operations as the
// one-order-at-a-time form they replace; only aₙ − bₙ (for Qback) has a
// formula of its own (sphere_terms).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/detail/log_derivative.hpp"

namespace attenuvis::mie::detail {

constexpr std::size_t kTermBlock = 64;
constexpr std::size_t kFirstTermBlock = 8;  // the first block of a series (series.hpp)

// The loops below are inlined into each instruction-set clone of
// term_block_double.cpp; a call to one shared copy would run its SSE2 code.
#if defined(__GNUC__)
#define ATTENUVIS_MIE_INLINE inline __attribute__((always_inline))
#else
#define ATTENUVIS_MIE_INLINE inline
#endif

// Inputs of one block, one entry per order n = first + i.
template <class Real>
struct TermInputs {
  Real rn[kTermBlock];                  // n
  Real yx[kTermBlock];                  // yₙ(x) = ψₙ₊₁/ψₙ
  Real R_re[kTermBlock], R_im[kTermBlock];      // Rₙ = ψₙ/ξₙ
  Real s[kTermBlock];                   // 1/|ξₙ|²
  Real rho_re[kTermBlock], rho_im[kTermBlock];  // ρₙ = ξₙ₋₁/ξₙ
  Real ymx_re[kTermBlock], ymx_im[kTermBlock];  // yₙ(mx)
  Real dy_re[kTermBlock], dy_im[kTermBlock];    // δₙ = yₙ(mx) − yₙ(x) where `difference`
  Real difference[kTermBlock];          // 1: numerators from δₙ (trap m-near-1); 0: from yₙ(mx)
  Real sign[kTermBlock];                // (−1)ⁿ
  void copy_entry(std::size_t from, std::size_t to) {
    for (Real* a : {rn, yx, R_re, R_im, s, rho_re, rho_im, ymx_re, ymx_im, dy_re, dy_im, difference, sign})
      a[to] = a[from];
  }
};

// Outputs: the coefficients and each order's term of every sum.
template <class Real>
struct TermOutputs {
  Real a_re[kTermBlock], a_im[kTermBlock], b_re[kTermBlock], b_im[kTermBlock];
  Real d_re[kTermBlock], d_im[kTermBlock];  // aₙ − bₙ, without cancellation (trap back-cancellation)
  Real ext[kTermBlock];      // (2n+1) Re(aₙ + bₙ), as |aₙ|²+|bₙ|² + (αₙ+βₙ)
  Real sca[kTermBlock];      // (2n+1)(|aₙ|² + |bₙ|²)
  Real abs[kTermBlock];      // (2n+1)(αₙ + βₙ)
  Real back_re[kTermBlock], back_im[kTermBlock];  // (−1)ⁿ (2n+1)(aₙ − bₙ), from d
  Real g_self[kTermBlock];   // (2n+1)/(n(n+1)) Re(aₙ b*ₙ)
  Real g_cross[kTermBlock];  // (n − 1/n) Re(aₙ₋₁a*ₙ + bₙ₋₁b*ₙ)  (n >= 2)
  Real size[kTermBlock];     // (2n+1)(|Re aₙ|+|Im aₙ|+|Re bₙ|+|Im bₙ|), for the convergence test
};

// Per-call constants of the term formulas.
template <class Real>
struct TermConstants {
  Real m_re, m_im;                      // m
  Real m1_re, m1_im;                    // m − 1
  Real c_re, c_im;                      // (m² − 1)/m  (trap m-near-1)
  Real e_re, e_im;                      // m² − 1
  // k/x and k/(mx) (ScaledInverse, ScaledInverseComplex in log_derivative.hpp).
  ScaledInverse<Real> over_x;
  ScaledInverseComplex<Real, Complex<Real>> over_mx;
};

// The coefficients of orders first .. first+count−1 of a sphere with index m.
// Real-and-imaginary arithmetic in the order of the complex expressions
//   a = R·num_a·(1/(Dₙ(mx) − m Gₙ)),   b = R·num_b·(1/(m Dₙ(mx) − Gₙ)).
template <class Real>
ATTENUVIS_MIE_INLINE void sphere_terms(const TermConstants<Real>& k, const TermInputs<Real>& in, std::size_t count,
                         TermOutputs<Real>& out) {
  const Real mr = k.m_re, mi = k.m_im, m1r = k.m1_re, m1i = k.m1_im, cr = k.c_re, ci = k.c_im;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (std::size_t i = 0; i < count; ++i) {
    const Real rn = in.rn[i], yx = in.yx[i];
    const Real n_over_x = k.over_x(rn), n1_over_x = k.over_x(rn + 1), w_over_x = k.over_x(2 * rn + 1);
    const Real Gr = in.rho_re[i] - n_over_x, Gi = in.rho_im[i];                    // Gₙ = ρₙ − n/x
    const Real cnr = cr * n1_over_x, cni = ci * n1_over_x;                          // (m²−1)(n+1)/(m x)
    const Real yr = in.ymx_re[i], yi = in.ymx_im[i], dr = in.dy_re[i], di = in.dy_im[i];
    // Numerators: from δ (m near 1) or from yₙ(mx); both evaluated, one kept.
    const Real na_d_r = (m1r * yx - dr) - cnr, na_d_i = (m1i * yx - di) - cni;     // (m−1)y − δ − cₙ
    const Real nb_d_r = -(mr * dr - mi * di) - m1r * yx, nb_d_i = -(mr * di + mi * dr) - m1i * yx;
    const Real na_v_r = (mr * yx - yr) - cnr, na_v_i = (mi * yx - yi) - cni;       // m y − yₙ(mx) − cₙ
    const Real nb_v_r = yx - (mr * yr - mi * yi), nb_v_i = Real(0) - (mr * yi + mi * yr);
    const bool d = in.difference[i] != 0;
    const Real nar = d ? na_d_r : na_v_r, nai = d ? na_d_i : na_v_i;
    const Real nbr = d ? nb_d_r : nb_v_r, nbi = d ? nb_d_i : nb_v_i;
    // Dₙ(mx) = (n+1)/(mx) − yₙ(mx); m yₙ(mx).
    const Complex<Real> np1_over_mx = k.over_mx(rn + 1);
    const Real dmr = np1_over_mx.real() - yr, dmi = np1_over_mx.imag() - yi;
    const Real myr = mr * yr - mi * yi, myi = mr * yi + mi * yr;
    // 1/(Dₙ(mx) − m Gₙ) and 1/((2n+1)/x − m yₙ(mx) − ρₙ) = 1/(m Dₙ(mx) − Gₙ).
    const Real Ar = dmr - (mr * Gr - mi * Gi), Ai = dmi - (mr * Gi + mi * Gr);
    const Real Br = (w_over_x - myr) - in.rho_re[i], Bi = (Real(0) - myi) - in.rho_im[i];
    const Real sa = 1 / (Ar * Ar + Ai * Ai), sb = 1 / (Br * Br + Bi * Bi);
    const Real iar = Ar * sa, iai = -Ai * sa, ibr = Br * sb, ibi = -Bi * sb;
    const Real Rr = in.R_re[i], Ri = in.R_im[i];
    const Real Rar = Rr * nar - Ri * nai, Rai = Rr * nai + Ri * nar;
    const Real Rbr = Rr * nbr - Ri * nbi, Rbi = Rr * nbi + Ri * nbr;
    const Real ar = Rar * iar - Rai * iai, ai = Rar * iai + Rai * iar;
    const Real br = Rbr * ibr - Rbi * ibi, bi = Rbr * ibi + Rbi * ibr;
    // Re aₙ − |aₙ|² = −Im(Dₙ(mx) m̄) s |1/A|²;  Re bₙ − |bₙ|² = Im(m yₙ(mx)) s |1/B|².
    const Real im_t_a = dmi * mr - dmr * mi;
    const Real alpha = -im_t_a * in.s[i] * (iar * iar + iai * iai);
    const Real beta = myi * in.s[i] * (ibr * ibr + ibi * ibi);
    out.a_re[i] = ar, out.a_im[i] = ai, out.b_re[i] = br, out.b_im[i] = bi;
    // aₙ − bₙ = Rₙ (m² − 1) Dₙ(mx) (Gₙ − Dₙ(x)) / ((Dₙ(mx) − m Gₙ)(m Dₙ(mx) − Gₙ)):
    // the numerators' difference num_a·B − num_b·A factors exactly, so aₙ − bₙ
    // keeps full relative accuracy where aₙ ≈ bₙ (m → 1, large x: there
    // Qback ~ 1e-9 Qext comes from Σ(−1)ⁿ(2n+1)(aₙ − bₙ), and forming aₙ − bₙ
    // by subtraction cost up to 9e-10 of Qback).  Gₙ − Dₙ(x) = ρₙ + yₙ(x) − (2n+1)/x.
    const Real gdr = (in.rho_re[i] + yx) - w_over_x, gdi = in.rho_im[i];
    const Real er = k.e_re, ei = k.e_im;
    const Real p1r = Rr * er - Ri * ei, p1i = Rr * ei + Ri * er;            // R (m² − 1)
    const Real p2r = p1r * dmr - p1i * dmi, p2i = p1r * dmi + p1i * dmr;    // · Dₙ(mx)
    const Real p3r = p2r * gdr - p2i * gdi, p3i = p2r * gdi + p2i * gdr;    // · (Gₙ − Dₙ(x))
    const Real p4r = p3r * iar - p3i * iai, p4i = p3r * iai + p3i * iar;    // / A
    out.d_re[i] = p4r * ibr - p4i * ibi, out.d_im[i] = p4r * ibi + p4i * ibr;  // / B
    const Real wn = 2 * rn + 1;
    const Real sca = wn * ((ar * ar + ai * ai) + (br * br + bi * bi));
    const Real abs_n = wn * (alpha + beta);
    out.sca[i] = sca, out.abs[i] = abs_n, out.ext[i] = sca + abs_n;
  }
}

// Perfectly conducting sphere: aₙ = Rₙ Dₙ(x)/Gₙ, bₙ = Rₙ, no absorption.
template <class Real>
ATTENUVIS_MIE_INLINE void conductor_terms(const TermConstants<Real>& k, const TermInputs<Real>& in, std::size_t count,
                            TermOutputs<Real>& out) {
  for (std::size_t i = 0; i < count; ++i) {
    const Real rn = in.rn[i];
    const Real dx = k.over_x(rn + 1) - in.yx[i];
    const Real Gr = in.rho_re[i] - k.over_x(rn), Gi = in.rho_im[i];
    const Real Rr = in.R_re[i], Ri = in.R_im[i];
    const Real Rdr = Rr * dx, Rdi = Ri * dx;
    const Real sg = 1 / (Gr * Gr + Gi * Gi);
    const Real igr = Gr * sg, igi = -Gi * sg;
    const Real ar = Rdr * igr - Rdi * igi, ai = Rdr * igi + Rdi * igr;
    out.a_re[i] = ar, out.a_im[i] = ai, out.b_re[i] = Rr, out.b_im[i] = Ri;
    out.d_re[i] = ar - Rr, out.d_im[i] = ai - Ri;
    const Real wn = 2 * rn + 1;
    const Real sca = wn * ((ar * ar + ai * ai) + (Rr * Rr + Ri * Ri));
    out.sca[i] = sca, out.abs[i] = Real(0), out.ext[i] = sca;
  }
}

// The remaining per-order terms (back-scattering, g, size of the term);
// a_prev/b_prev: the coefficients of order first − 1 (zero for first = 1).
template <class Real>
ATTENUVIS_MIE_INLINE void sum_terms(const TermInputs<Real>& in, std::size_t count, const Complex<Real>& a_prev,
                      const Complex<Real>& b_prev, TermOutputs<Real>& out) {
  using std::abs;
  for (std::size_t i = 0; i < count; ++i) {
    const Real rn = in.rn[i], wn = 2 * rn + 1;
    const Real ar = out.a_re[i], ai = out.a_im[i], br = out.b_re[i], bi = out.b_im[i];
    out.back_re[i] = in.sign[i] * wn * out.d_re[i];
    out.back_im[i] = in.sign[i] * wn * out.d_im[i];
    const Real inv_n = 1 / rn, inv_n1 = 1 / (rn + 1);
    out.g_self[i] = (inv_n + inv_n1) * (ar * br + ai * bi);
    out.g_cross[i] = rn - inv_n;  // times the cross product below
    out.size[i] = wn * (abs(ar) + abs(ai) + abs(br) + abs(bi));
  }
  if (count == 0) return;
  out.g_cross[0] *= a_prev.real() * out.a_re[0] + a_prev.imag() * out.a_im[0] + b_prev.real() * out.b_re[0] +
                    b_prev.imag() * out.b_im[0];
  for (std::size_t i = 1; i < count; ++i)
    out.g_cross[i] *= out.a_re[i - 1] * out.a_re[i] + out.a_im[i - 1] * out.a_im[i] +
                      out.b_re[i - 1] * out.b_re[i] + out.b_im[i - 1] * out.b_im[i];
}

// The seven compensated sums of the series, by lane: SeriesSums (series.hpp)
// keeps them in this order, VectorSums as lanes 0–6 of its two 4-wide vectors
// (lane 7 unused).
struct SumLane {
  enum : int { ext, sca, abs, back_re, back_im, g_cross, g_self, count };
};

// The convergence test of the converged term rule: order n, beyond x, is the
// last one summed once its size (TermOutputs::size) is at most tol times the
// scale of the sums, min(|Σext|, |Σback_re| + |Σback_im|), read from the
// running sums without their carries.  SeriesSums and sum_block_double call
// it; the lanes of spheres() run the same test on vectors
// (sphere_lanes_kernels.inc, where no helper from outside may be called).
template <class Real>
ATTENUVIS_MIE_INLINE bool series_converged(std::size_t n, double x, const Real& size, const Real& tol,
                                           const Real& ext, const Real& back_re, const Real& back_im) {
  using std::abs;
  return static_cast<double>(n) > x && size <= tol * (std::min)(abs(ext), abs(back_re) + abs(back_im));
}

template <class Real>
struct SeriesSums;

// Pass 3 of series.hpp for double (with or without extras): its seven
// compensated (Kahan) sums, lane c of `sum`/`carry` the sum SumLane c.  Two
// 4-wide vector operations advance all seven — the same IEEE operations per
// sum as KahanSum::add, so the same bits — where the scalar loop took seven.
struct VectorSums {
  alignas(64) double sum[8] = {}, carry[8] = {};
  bool converged = false;  // the convergence test stopped the series
  void to(SeriesSums<double>& s) const;  // series.hpp
};

// The double instances, compiled in mie/src/term_block_double.cpp for SSE2,
// AVX2 and AVX-512 and chosen at run time by the CPU (GCC target_clones).
// Built with -ffp-contract=off, every instance performs the same IEEE
// operations in the same order, so the results do not depend on the CPU.
void sphere_terms_double(const TermConstants<double>& k, const TermInputs<double>& in, std::size_t count,
                         TermOutputs<double>& out);
void conductor_terms_double(const TermConstants<double>& k, const TermInputs<double>& in, std::size_t count,
                            TermOutputs<double>& out);
void sum_terms_double(const TermInputs<double>& in, std::size_t count, const Complex<double>& a_prev,
                      const Complex<double>& b_prev, TermOutputs<double>& out);
// Adds orders first .. first+count−1 of `t` to `s`, stopping after the first
// order that passes series_converged (converged_rule; sets s.converged).
// Returns the number of orders added.
std::size_t sum_block_double(const TermOutputs<double>& t, std::size_t first, std::size_t count, double x,
                             double tol, bool converged_rule, VectorSums& s);

}  // namespace attenuvis::mie::detail
