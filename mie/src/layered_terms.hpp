// Pass 2 of the layered-sphere series (layered_series.hpp) for a block of
// consecutive orders: the log-derivative transfer through every shell and the
// Mie coefficients aₙ, bₙ at the surface.  Every order is independent of the
// others, so the loops are plain arithmetic on arrays that the compiler
// vectorises across orders (layered_terms_double.cpp compiles them once per
// instruction set, as term_block_double.cpp does for the homogeneous sphere).
//
// Notation.  Every mode carries, instead of the logarithmic derivative H of
// its radial function f at the outer radius of a layer (argument z = m_l x_l),
// its "y-form" Y = (n+1)/z − H = f_{n+1}/f_n (log_derivative.hpp: for f = ψ
// this is yₙ(z)).  Y is ~z/(2n+3) where H is ~(n+1)/z, so nothing of size
// 1/x is formed and subtracted (trap small-x of series.hpp, layered trap
// small-x-b in layered_series.hpp).
//
// Interface between layer l−1 (index m_{l−1}) and layer l (index m_l) at
// x_{l−1}, z1 = m_l x_{l−1}: continuity of the tangential fields (B&H 8.1;
// Yang 2003 eq. 12) sets the log derivative of the layer-l function at z1 to
//     T_a = (m_l/m_{l−1}) H_a,   T_b = (m_{l−1}/m_l) H_b,
// i.e. in y-form, with r = m_l/m_{l−1},
//     Yin_a = (n+1) κ + r Y_a,   κ = (m_{l−1}² − m_l²)/(m_l m_{l−1}² x_{l−1}),
//     Yin_b = Y_b / r
// (the (n+1)/z terms of the b mode cancel exactly and are never formed; κ's
// difference of squares is formed as (m_{l−1} − m_l)(m_{l−1} + m_l), trap
// contrast-near-1).  A perfectly conducting core gives T_a = 0 (Yin_a =
// (n+1)/z1) and T_b = ∞ (f_n(z1) = 0).
//
// Transfer across layer l.  Write the layer's radial function in a basis
// (ψ, B) of Riccati–Bessel functions, f = ψ − q B, with B = ξ (B&H's
// ξ = ψ − iχ) in absorbing shells and B = χ in nearly real ones
// (layered_series.hpp, trap spurious-absorption).  With y1 = ψ_{n+1}/ψ_n and
// y3 = B_{n+1}/B_n, f_{n+1}/f_n = (y1 − q' y3)/(1 − q') where q' = q B_n/ψ_n,
// so matching Yin at z1 gives q'(z1) = u/v with u = y1(z1) − Yin,
// v = y3(z1) − Yin, and at z2 = m_l x_l q'(z2) = Q u/v with
// Qₙ = (ψₙ/Bₙ)(z1) / (ψₙ/Bₙ)(z2) (Yang's Q for B = ξ):
//     Yout = (y1(z2) v − Q u y3(z2)) / (v − Q u)          (cf. Yang 2003 eq. 13)
// One complex division per mode and shell.  Q → 0 (thick absorbing shells,
// n ≫ |z2|) gives Yout = y1(z2): the shell hides what is inside.
//
// Surface (outer layer m = m_L, real x = x_L).  As for the homogeneous sphere
// (series.hpp, term_block.hpp) with yₙ(mx) replaced by Y_a in aₙ and by Y_b
// in bₙ:
//     aₙ = Rₙ (m yₙ(x) − Y_a − cₙ) / (Dₐ − m Gₙ),   Dₐ = (n+1)/(mx) − Y_a,
//     bₙ = Rₙ (yₙ(x) − m Y_b) / ((2n+1)/x − m Y_b − ρₙ),
// cₙ = (m² − 1)(n+1)/(mx), Gₙ = ρₙ − n/x.  Absorption from the Wronskian
// (trap weak-absorption): Re aₙ − |aₙ|² = −Im(Dₐ m̄) sₙ/|A|²,
// Re bₙ − |bₙ|² = Im(m Y_b) sₙ/|B|².  aₙ − bₙ from its factored form
// Rₙ (Y_a + cₙ − m² Y_b)(Gₙ − Dₙ(x))/(A B) (trap back-cancellation; with
// Y_a = Y_b = yₙ(mx) it is term_block.hpp's).
#pragma once

#include <cstddef>

#include "term_block.hpp"

namespace attenuvis::mie::detail {

// One shell's per-order inputs of a block: y1 = yₙ, y3 = Bₙ₊₁/Bₙ at z1 (inner
// radius) and z2 (outer radius), and Qₙ.
template <class Real>
struct ShellInputs {
  Real y1i_re[kTermBlock], y1i_im[kTermBlock], y3i_re[kTermBlock], y3i_im[kTermBlock];
  Real y1o_re[kTermBlock], y1o_im[kTermBlock], y3o_re[kTermBlock], y3o_im[kTermBlock];
  Real q_re[kTermBlock], q_im[kTermBlock];
};

// One shell's constants: Yin_a = (n+1) κ + r Y_a, Yin_b = Y_b r⁻¹.  conductor:
// the shell lies on a perfectly conducting core (κ, r unused).
template <class Real>
struct ShellConstants {
  Real kappa_re, kappa_im, r_re, r_im, inv_r_re, inv_r_im;
  bool conductor;
  ScaledInverseComplex<Real, Complex<Real>> over_z1;  // k/(m_l x_{l−1}): Yin_a on a conductor
};

// The y-forms Y_a, Y_b of both modes for a block of orders, at the outer
// radius of the layer reached so far.
template <class Real>
struct Modes {
  Real a_re[kTermBlock], a_im[kTermBlock], b_re[kTermBlock], b_im[kTermBlock];
};

// Yout = (y1o v − Q u y3o)/(v − Q u), u = y1i − Yin, v = y3i − Yin, written
// out in real parts; `vanishes`: u = v = 1 (f vanishes at z1: the b mode on
// a conductor).
template <class Real, bool vanishes>
ATTENUVIS_MIE_INLINE void transfer_mode(const ShellInputs<Real>& s, std::size_t i, Real yr, Real yi, Real& out_r,
                                        Real& out_i) {
  Real ur = Real(1), ui = Real(0), vr = Real(1), vi = Real(0);
  if constexpr (!vanishes) {
    ur = s.y1i_re[i] - yr, ui = s.y1i_im[i] - yi;
    vr = s.y3i_re[i] - yr, vi = s.y3i_im[i] - yi;
  }
  const Real qr = s.q_re[i], qi = s.q_im[i];
  const Real qur = qr * ur - qi * ui, qui = qr * ui + qi * ur;  // Q u
  const Real y1r = s.y1o_re[i], y1i = s.y1o_im[i], y3r = s.y3o_re[i], y3i = s.y3o_im[i];
  const Real nr = (y1r * vr - y1i * vi) - (qur * y3r - qui * y3i);
  const Real ni = (y1r * vi + y1i * vr) - (qur * y3i + qui * y3r);
  const Real dr = vr - qur, di = vi - qui;
  const Real sd = 1 / (dr * dr + di * di);
  out_r = (nr * dr + ni * di) * sd;
  out_i = (ni * dr - nr * di) * sd;
}

// The modes through one shell, orders first .. first + count − 1 (entry i is
// order first + i); on_conductor: the shell lies on a perfectly conducting
// core (T_a = 0: Yin_a = (n+1)/z1; T_b = ∞).
template <class Real, bool on_conductor>
ATTENUVIS_MIE_INLINE void shell_transfer_for(const ShellConstants<Real>& k, const ShellInputs<Real>& s,
                                             std::size_t first, std::size_t count, Modes<Real>& y) {
  const Real kr = k.kappa_re, ki = k.kappa_im, rr = k.r_re, ri = k.r_im, jr = k.inv_r_re, ji = k.inv_r_im;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (std::size_t i = 0; i < count; ++i) {
    const Real n1 = index_real<Real>(first + i + 1);
    const Real yar = y.a_re[i], yai = y.a_im[i], ybr = y.b_re[i], ybi = y.b_im[i];
    Real ina_r, ina_i;
    if constexpr (on_conductor) {
      const Complex<Real> t = k.over_z1(n1);
      ina_r = t.real(), ina_i = t.imag();
    } else {
      ina_r = (n1 * kr) + (rr * yar - ri * yai), ina_i = (n1 * ki) + (rr * yai + ri * yar);
    }
    const Real inb_r = jr * ybr - ji * ybi, inb_i = jr * ybi + ji * ybr;
    transfer_mode<Real, false>(s, i, ina_r, ina_i, y.a_re[i], y.a_im[i]);
    transfer_mode<Real, on_conductor>(s, i, inb_r, inb_i, y.b_re[i], y.b_im[i]);
  }
}

template <class Real>
ATTENUVIS_MIE_INLINE void shell_transfer(const ShellConstants<Real>& k, const ShellInputs<Real>& s,
                                         std::size_t first, std::size_t count, Modes<Real>& y) {
  if (k.conductor) shell_transfer_for<Real, true>(k, s, first, count, y);
  else shell_transfer_for<Real, false>(k, s, first, count, y);
}

// The surface: inputs per order as for the homogeneous sphere (TermInputs:
// rn, yx, R, s, ρ, sign; its ymx/dy fields unused) and the modes Y_a, Y_b.
template <class Real>
struct SurfaceConstants {
  Real m_re, m_im;    // m_L
  Real c_re, c_im;    // (m_L² − 1)/m_L
  Real e_re, e_im;    // m_L²
  ScaledInverse<Real> over_x;
  ScaledInverseComplex<Real, Complex<Real>> over_mx;
};

template <class Real>
ATTENUVIS_MIE_INLINE void surface_terms(const SurfaceConstants<Real>& k, const TermInputs<Real>& in,
                                        const Modes<Real>& y, std::size_t count, TermOutputs<Real>& out) {
  const Real mr = k.m_re, mi = k.m_im, cr = k.c_re, ci = k.c_im, er = k.e_re, ei = k.e_im;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (std::size_t i = 0; i < count; ++i) {
    const Real rn = in.rn[i], yx = in.yx[i];
    const Real n_over_x = k.over_x(rn), n1_over_x = k.over_x(rn + 1), w_over_x = k.over_x(2 * rn + 1);
    const Real Gr = in.rho_re[i] - n_over_x, Gi = in.rho_im[i];  // Gₙ = ρₙ − n/x
    const Real cnr = cr * n1_over_x, cni = ci * n1_over_x;        // cₙ
    const Real yar = y.a_re[i], yai = y.a_im[i], ybr = y.b_re[i], ybi = y.b_im[i];
    const Real nar = (mr * yx - yar) - cnr, nai = (mi * yx - yai) - cni;  // m yₙ(x) − Y_a − cₙ
    const Real myr = mr * ybr - mi * ybi, myi = mr * ybi + mi * ybr;      // m Y_b
    const Real nbr = yx - myr, nbi = Real(0) - myi;
    const Complex<Real> np1_over_mx = k.over_mx(rn + 1);
    const Real dar = np1_over_mx.real() - yar, dai = np1_over_mx.imag() - yai;  // Dₐ
    const Real Ar = dar - (mr * Gr - mi * Gi), Ai = dai - (mr * Gi + mi * Gr);
    const Real Br = (w_over_x - myr) - in.rho_re[i], Bi = (Real(0) - myi) - in.rho_im[i];
    const Real sa = 1 / (Ar * Ar + Ai * Ai), sb = 1 / (Br * Br + Bi * Bi);
    const Real iar = Ar * sa, iai = -Ai * sa, ibr = Br * sb, ibi = -Bi * sb;
    const Real Rr = in.R_re[i], Ri = in.R_im[i];
    const Real Rar = Rr * nar - Ri * nai, Rai = Rr * nai + Ri * nar;
    const Real Rbr = Rr * nbr - Ri * nbi, Rbi = Rr * nbi + Ri * nbr;
    const Real ar = Rar * iar - Rai * iai, ai = Rar * iai + Rai * iar;
    const Real br = Rbr * ibr - Rbi * ibi, bi = Rbr * ibi + Rbi * ibr;
    const Real alpha = -(dai * mr - dar * mi) * in.s[i] * (iar * iar + iai * iai);
    const Real beta = myi * in.s[i] * (ibr * ibr + ibi * ibi);
    out.a_re[i] = ar, out.a_im[i] = ai, out.b_re[i] = br, out.b_im[i] = bi;
    // aₙ − bₙ = Rₙ (Y_a + cₙ − m² Y_b)(Gₙ − Dₙ(x)) / (A B).
    const Real tr = (yar + cnr) - (er * ybr - ei * ybi), ti = (yai + cni) - (er * ybi + ei * ybr);
    const Real gdr = (in.rho_re[i] + yx) - w_over_x, gdi = in.rho_im[i];
    const Real p1r = Rr * tr - Ri * ti, p1i = Rr * ti + Ri * tr;
    const Real p2r = p1r * gdr - p1i * gdi, p2i = p1r * gdi + p1i * gdr;
    const Real p3r = p2r * iar - p2i * iai, p3i = p2r * iai + p2i * iar;
    out.d_re[i] = p3r * ibr - p3i * ibi, out.d_im[i] = p3r * ibi + p3i * ibr;
    const Real wn = 2 * rn + 1;
    const Real sca = wn * ((ar * ar + ai * ai) + (br * br + bi * bi));
    const Real abs_n = wn * (alpha + beta);
    out.sca[i] = sca, out.abs[i] = abs_n, out.ext[i] = sca + abs_n;
  }
}

// The double instances, one clone per instruction set
// (layered_terms_double.cpp); the same IEEE operations on every CPU.
void shell_transfer_double(const ShellConstants<double>& k, const ShellInputs<double>& s, std::size_t first,
                           std::size_t count, Modes<double>& y);
void surface_terms_double(const SurfaceConstants<double>& k, const TermInputs<double>& in, const Modes<double>& y,
                          std::size_t count, TermOutputs<double>& out);

}  // namespace attenuvis::mie::detail
