// The second solution of each shell of a layered sphere (ξ or χ, see trap
// spurious-absorption in layered_series.hpp), its start ρ₀ = B₋₁/B₀, the
// factor e^{2iz} − 1 in extended precision, and ψ₁/B₀: the pieces of
// Yang's running product Qₙ that layered_series.hpp assembles.  Private to
// the library, templated on the floating type as layered_series.hpp is.
#pragma once

#include <cmath>
#include <complex>
#include <type_traits>

#include "layered_terms.hpp"
#include "series.hpp"

namespace attenuvis::mie::detail {

// The type that e^{2iz} and the thickness phase are formed in: extended for
// double (phase accuracy at large |z|, see ScaledInverse), Real otherwise.
template <class Real>
struct WideOf {
  using type = Real;
};
template <>
struct WideOf<double> {
  using type = long double;
};

// Where |Re(m) t| is at most this, the phase a = Re(m) t and its sines are
// formed in double even for Real = double: the rounding of a, <= |a| ε/2 =
// 1.1e-13, is below what the recurrences leave, and the long double
// transcendentals were a fifth of a two-layer call at x = 1.
constexpr double kNarrowPhase = 1024;

// e^{2iw} − 1 for w = m t (Im w >= 0), accurate for small w (trap
// small-z-exp): Re = expm1(−2b) cos 2a − 2 sin² a, Im = e^{−2b} sin 2a,
// formed in W.
template <class Real, class W>
Complex<Real> twice_exp_minus_1_in(const W& t, const Complex<Real>& m) {
  using std::cos;
  using std::exp;
  using std::expm1;
  using std::sin;
  const W a = W(m.real()) * t, b = W(m.imag()) * t;
  const W sa = sin(a);
  const W c2 = cos(a + a), s2 = sin(a + a);
  const W re = expm1(W(-2) * b) * c2 - W(2) * sa * sa;
  const W im = exp(W(-2) * b) * s2;
  return Complex<Real>(static_cast<Real>(re), static_cast<Real>(im));
}

template <class Real>
Complex<Real> twice_exp_minus_1(const typename WideOf<Real>::type& t, const Complex<Real>& m) {
  if constexpr (std::is_same_v<Real, double>) {
    const double td = static_cast<double>(t);
    if (std::abs(m.real() * td) <= kNarrowPhase) return twice_exp_minus_1_in<Real, double>(td, m);
  }
  return twice_exp_minus_1_in<Real, typename WideOf<Real>::type>(t, m);
}

// A shell's second solution B (ξ or χ) at z = m x: what its start needs,
// computed before the tables (the transcendental part): ρ₀ = B₋₁/B₀ for the
// upward recurrence, and the branch and value from which ψ₁/B₀ is formed
// once y₀ is known (psi1_over_b0).
template <class Real>
struct SecondSolution {
  Complex<Real> rho0;  // B₋₁/B₀
  Complex<Real> c;     // χ: tan z;  ξ: e^{2iz} − 1
  bool chi;            // B = χ, else ξ
  bool sin_branch;     // |sin z| >= |cos z|
};

// B = ξ (absorbing shells): ρ₀ = ξ₋₁/ξ₀ = i, and e^{2iz} − 1 for the scaled
// start s(z) = e^{2iz} ψ₁/ξ₀ (|e^{2iz}| <= 1 keeps it finite; Q's start
// restores the scale); |sin z| >= |cos z| where Re e^{2iz} <= 0.
template <class Real>
SecondSolution<Real> hankel_solution(const Real& x, const Complex<Real>& m) {
  using C = Complex<Real>;
  using W = typename WideOf<Real>::type;
  const C em1 = twice_exp_minus_1<Real>(W(x), m);
  return {C(Real(0), Real(1)), em1, false, em1.real() + Real(1) <= Real(0)};
}

// B = χ (nearly real shells, trap spurious-absorption): ρ₀ = χ₋₁/χ₀ = −tan z.
// tan z is formed from Re z, Im z in WideOf precision beyond kNarrowPhase
// (phase accuracy); Im z <= kChiBasisMaxImZ keeps cosh, sinh small.
template <class Real, class W>
SecondSolution<Real> neumann_solution_in(const W& x, const Complex<Real>& m) {
  using C = Complex<Real>;
  using std::cos;
  using std::cosh;
  using std::sin;
  using std::sinh;
  const W a = W(m.real()) * x, b = W(m.imag()) * x;
  const W sa = sin(a), ca = cos(a), chb = cosh(b), shb = sinh(b);
  const W sr = sa * chb, si = ca * shb;   // sin z
  const W cr = ca * chb, ci = -sa * shb;  // cos z
  const W d = W(1) / (cr * cr + ci * ci);
  const C tan_z(static_cast<Real>((sr * cr + si * ci) * d), static_cast<Real>((si * cr - sr * ci) * d));
  return {-tan_z, tan_z, true, sa * sa >= ca * ca};
}

template <class Real>
SecondSolution<Real> neumann_solution(const Real& x, const Complex<Real>& m) {
  if constexpr (std::is_same_v<Real, double>) {
    if (std::abs(m.real() * x) <= kNarrowPhase) return neumann_solution_in<Real, double>(x, m);
  }
  return neumann_solution_in<Real, typename WideOf<Real>::type>(typename WideOf<Real>::type(x), m);
}

// ψ₁/B₀ from y₀ = ψ₁/ψ₀ without dividing by ψ₀ = sin z where it is small
// (trap sin-zero; riccati_psi1 in series.hpp): ψ₁ = sin z · y₀ where
// |sin z| >= |cos z|, else ψ₁ = cos z · y₀/(1/z − y₀).  With ξ₀ = −i e^{iz}
// (scaled by e^{2iz}): (e^{2iz} − 1)/2 · y₀, or i(e^{2iz} + 1)/2 ·
// y₀/(1/z − y₀); with χ₀ = cos z: tan z · y₀, or y₀/(1/z − y₀).
template <class Real>
Complex<Real> psi1_over_b0(const SecondSolution<Real>& b, const Complex<Real>& y0, const Complex<Real>& inv_z) {
  using C = Complex<Real>;
  if (b.chi) return b.sin_branch ? cmul(b.c, y0) : cmul(y0, recip(C(inv_z - y0)));
  const C half(Real(0.5), Real(0));
  if (b.sin_branch) return cmul(cmul(b.c, y0), half);
  const C ep1 = b.c + C(Real(2));
  const C i_ep1_half(-ep1.imag() * Real(0.5), ep1.real() * Real(0.5));
  return cmul(i_ep1_half, cmul(y0, recip(C(inv_z - y0))));
}

// Shells whose Im(m_l) x_l is at most this use the basis (ψ, χ), the others
// (ψ, ξ).  In (ψ, χ) every quantity of a non-absorbing shell is real, so no
// rounding error becomes an imaginary part (absorption); it loses digits
// like e^{2 Im z} where the field must decay outward (≤ e² here).
constexpr double kChiBasisMaxImZ = 1.0;

}  // namespace attenuvis::mie::detail
