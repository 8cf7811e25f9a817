// The Mie series of a layered (core–shell, multilayer) sphere, templated on
// the floating type.
//
// Private to the library: instantiated by layered_double.cpp (double, and
// long double where double cannot keep 1e-10) and layered_referee.cpp (the
// 50-digit referee of the same equations).
//
// Layers l = 0 .. L−1 from the core out; x_l = 2π r_l/λ is the size parameter
// of the OUTER radius of layer l, m_l its index relative to the medium; the
// particle's size parameter is x = x_{L−1}.  Method: Yang (2003, Appl. Opt.
// 42:1710), the log-derivative recursion through the layers, rewritten in the
// ratio variables of the homogeneous core (series.hpp, log_derivative.hpp):
//   * For every complex argument z of the recurrences (m_0 x_0 in the core;
//     z1 = m_l x_{l−1} and z2 = m_l x_l in shell l) and for the real x:
//     yₙ(z) = ψₙ₊₁/ψₙ downward from a Lentz (or, in double where
//     miller_depth() proves it, Miller) start.  Each shell's second solution
//     B (ξ or χ, see trap spurious-absorption) through ρₙ(z) = Bₙ₋₁/Bₙ
//     upward from ρ₀ = B₋₁/B₀ (B dominant for n > |z|, neither growing nor
//     decaying relative to ψ below: stable), and y3ₙ = Bₙ₊₁/Bₙ =
//     (2n+1)/z − ρₙ = 1/ρₙ₊₁ (no extra division).
//   * Yang's Qₙ = (ψₙ/Bₙ)(z1) / (ψₙ/Bₙ)(z2) as ONE running product:
//     Q₁ = [phase] [(ψ₁/B₀)(z1)/(ψ₁/B₀)(z2)] ρ₁(z1)/ρ₁(z2),
//     Qₙ = Qₙ₋₁ ρₙ(z1) yₙ₋₁(z1) / (ρₙ(z2) yₙ₋₁(z2)),
//     with ψ₁/ξ₀ scaled by e^{2iz} (|e^{2iz}| <= 1) and the phase
//     e^{2i(z2−z1)} restoring it (B = ξ), no scale for B = χ.  Carrying Q
//     itself (not the two products ψₙ/Bₙ, which underflow for n ≫ |z1| and
//     overflow as e^{2 Im z}) means Q underflows only once it no longer
//     matters (|Q| ~ (x_{l−1}/x_l)^{2n+1} or e^{−2 Im(z2−z1)}).
//   * The transfer through each shell and the surface coefficients:
//     layered_terms.hpp, in y-form, vectorised across orders.
//   * Sums, convergence test, S1/S2: those of the homogeneous core
//     (series.hpp, angular_sums.hpp), so the angular machinery (scattering
//     matrix, Legendre moments) takes the layered aₙ, bₙ unchanged.
// Error analysis.  Every quantity is a ratio of size O(1) in its natural
// scale, so the per-order rounding is a few ε relative in each of yₙ, ρₙ,
// y3ₙ, and the transfer is a Möbius map whose condition is
// |f|-cancellation: |Yout| against (|y1(z2)||v| + |Q u y3(z2)|)/|v − Q u|,
// large only where f_n(z2) ≈ 0 in a sum of larger parts (a resonance of the
// shell, where the 50-digit referee measures what remains).  The running
// products Q and Rₙ = ψₙ/ξₙ(x) and the downward yₙ accumulate rounding like
// √N ε, amplified in Qback by the cancellation of its alternating sum (trap
// back-cancellation): at large x the recurrences run in long double
// (layered_double.cpp), as the homogeneous core's do.
//
// The layered traps: numerical pitfalls of coated- and multilayer-sphere codes
// (Toon & Ackerman 1981; Kaiser & Schweiger 1993, Comput. Phys. 7:682; Yang
// 2003; Peña & Pal 2009, Comput. Phys. Commun. 180:2348), and how each is
// avoided.  Tests (tests/mie/test_layered_*.cpp) check them against the
// 50-digit referee; the homogeneous traps of series.hpp apply layer by layer.
//   absorbing-core      BHCOAT (B&H appendix B) forms χₙ(m₁x₁), χₙ(m₂x₁)
//                       and ψₙ of complex argument, which grow as e^{Im z}:
//                       it overflows or loses every digit once Im(m x) is a
//                       few tens (a large soot core).  Here only ratios
//                       appear, and Q carries e^{−2 Im(z2 − z1)} <= 1.
//   thin-shell          z1 ≈ z2: e^{2i(z2−z1)} is formed from m_l (x_l −
//                       x_{l−1}) in extended precision (the difference of the
//                       two doubles, exact there), never from z2 − z1 rounded
//                       separately; Q → 1 and Yout → Yin continuously (a
//                       zero-thickness shell gives the core to rounding).
//   contrast-near-1     m_l ≈ m_{l−1}: κ = (m_{l−1}² − m_l²)/(m_l m_{l−1}² x)
//                       is formed from the factored difference; u = y1(z1) −
//                       Yin is small and enters only multiplied by Q u, so
//                       its cancellation costs no more than the rounding of
//                       y1(z2) itself (shell index = core index gives the
//                       homogeneous sphere to rounding).
//   small-x-b           The b-mode (n+1)/z terms of the boundary condition
//                       cancel exactly (T_b = (m_{l−1}/m_l) H_b); in y-form
//                       they are never formed, where Yang's D-form loses
//                       1/x² (1e8 ε at x = 1e-4) in bₙ and so in g.
//   sin-zero            ψ₁/B₀ divides by ψ₀(z) = sin z through y₀ = ψ₁/ψ₀ for
//                       real or nearly real z ≈ jπ (a non-absorbing layer);
//                       riccati_psi1's second branch (series.hpp),
//                       ψ₁ = cos z · y₀/(1/z − y₀), is used where
//                       |cos z| > |sin z| (hankel_start, neumann_start).
//   spurious-absorption In the basis (ψ, ξ) every real quantity is a
//                       combination of complex ones (ξ = ψ − iχ, and Q, y3
//                       carry O(1) imaginary parts that cancel), so rounding
//                       leaves an imaginary part ~ε|Y| in the y-form of a
//                       non-absorbing shell: a spurious absorption that,
//                       relative to Qext, grows like ε/x³ at small x (2e-3
//                       at x = 1e-4, measured) and like ε/|m − 1| near m = 1.
//                       Shells with Im(m_l) x_l <= kChiBasisMaxImZ use the
//                       real basis (ψ, χ), in which a real shell's arithmetic
//                       is real (absorption exactly 0) and a weakly absorbing
//                       one keeps its imaginary parts to relative accuracy.
//                       The others use ξ, where the outward decay e^{−2 Im z}
//                       of the field is carried by Q instead of by a
//                       cancellation between growing functions.
//   small-z-exp         e^{2iz} − 1 ≈ 2iz for small z: formed with expm1
//                       and 2 sin²(Re z) (no 1 − cos cancellation).
//   large-shell-z       A Lentz start needs ~|z| − N steps where |z| > N
//                       (a high-index layer near the surface); its cost is
//                       bounded by the domain |m x| (layered_double.cpp).
//   back-cancellation   As for the homogeneous sphere; aₙ − bₙ has a factored
//                       form (layered_terms.hpp).
#pragma once

#include <cmath>
#include <complex>
#include <cstddef>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

#include "attenuvis/io/check.hpp"
#include "layered_second_solution.hpp"
#include "layered_terms.hpp"
#include "series.hpp"

namespace attenuvis::mie::detail {

// One downward pass for K complex arguments at once, their state in
// registers: the chains are independent, so their division latencies
// overlap.  Per argument j:
//  * yₙ(z), n = 0 .. N, into y[j]: from 0 at N + miller[j] (miller_depth),
//    or from Lentz's continued fraction at N + 1 (miller[j] = 0);
//  * where rho[j] is given (a shell's z1, z2), the upward ratio of its second
//    solution, ρₖ = 1/((2k−1)/z − ρₖ₋₁), k = 1 .. N + 1, from rho[j][0] = ρ₀,
//    in the same loop (as downward_ratios does for ξ(x)): the upward pass of
//    the series then has no division of its own.
// The first group also carries the real x (`surface`): yₙ(x) in real
// arithmetic (at a zero of ψₙ(x) the pole of yₙ(x) must stay a finite 1/den;
// a complex reciprocal squares den and would overflow), and ρₖ(x) upward
// from i.  Each chain performs the same operations whatever its neighbours.
template <class Real>
struct SurfaceChains {
  const ScaledInverse<Real>* over_x;
  std::size_t miller;
  Real* y;                     // yₙ(x)
  StoredComplex<Real>* rho;    // ρₖ(x), k = 0 .. N + 1
};

template <class Real, int K>
void downward_group(const ScaledInverseComplex<Real, Complex<Real>>* over, const std::size_t* miller, std::size_t N,
                    StoredComplex<Real>* const* tables, StoredComplex<Real>* const* rho,
                    const SurfaceChains<Real>* surface) {
  using C = Complex<Real>;
  C y[K], r[K];
  Real yx(0);
  const auto step = [&](int j, std::size_t n) {  // yₙ₋₁ from yₙ
    C den = over[j](index_real<Real>(2 * n + 1)) - y[j];
    avoid_zero<C, Real>(den);
    y[j] = recip(den);
  };
  const auto step_real = [&](std::size_t n) {
    Real den = (*surface->over_x)(index_real<Real>(2 * n + 1)) - yx;
    avoid_zero<Real, Real>(den);
    yx = Real(1) / den;
  };
  std::size_t top = surface ? N + surface->miller : N;
  for (int j = 0; j < K; ++j) {
    y[j] = C(Real(0)), top = std::max(top, N + miller[j]);
    if (rho[j]) r[j] = C(rho[j][0].real(), rho[j][0].imag());
  }
  for (std::size_t n = top; n > N; --n) {
    for (int j = 0; j < K; ++j)
      if (n <= N + miller[j]) step(j, n);
    if (surface && n <= N + surface->miller) step_real(n);
  }
  for (int j = 0; j < K; ++j)
    if (miller[j] == 0) y[j] = recip(riccati_psi_ratio<C, Real>(N + 1, over[j]));
  if (surface && surface->miller == 0) yx = Real(1) / riccati_psi_ratio<Real, Real>(N + 1, *surface->over_x);
  HankelRatio<Real, C> hankel;
  if (surface) store(surface->rho[0], hankel.rho);
  for (std::size_t n = N;; --n) {
    const std::size_t k = N + 1 - n;  // the upward order
    for (int j = 0; j < K; ++j) {
      store(tables[j][n], y[j]);
      if (rho[j]) {
        r[j] = recip(C(over[j](index_real<Real>(2 * k - 1)) - r[j]));
        store(rho[j][k], r[j]);
      }
    }
    if (surface) surface->y[n] = yx, store(surface->rho[k], hankel.next(k, *surface->over_x));
    if (n == 0) break;
    for (int j = 0; j < K; ++j) step(j, n);
    if (surface) step_real(n);
  }
}

// Every argument's chains, in groups of up to four (the surface's in the first).
template <class Real>
void downward_complex(const SurfaceChains<Real>& surface,
                      const std::vector<ScaledInverseComplex<Real, Complex<Real>>>& over, const std::size_t* miller,
                      std::size_t N, StoredComplex<Real>* const* tables, StoredComplex<Real>* const* rho) {
  ATTENUVIS_CHECK(!over.empty());  // every layered sphere has a core or a shell: x rides in the first group
  for (std::size_t j = 0; j < over.size(); j += 4) {
    const SurfaceChains<Real>* sc = j == 0 ? &surface : nullptr;
    switch (std::min<std::size_t>(4, over.size() - j)) {
      case 1: downward_group<Real, 1>(&over[j], miller + j, N, tables + j, rho + j, sc); break;
      case 2: downward_group<Real, 2>(&over[j], miller + j, N, tables + j, rho + j, sc); break;
      case 3: downward_group<Real, 3>(&over[j], miller + j, N, tables + j, rho + j, sc); break;
      default: downward_group<Real, 4>(&over[j], miller + j, N, tables + j, rho + j, sc); break;
    }
  }
}

// The upward pass of one shell in its basis (ψ, B), B = ξ or χ, from the
// tables of the downward pass: ρₙ = Bₙ₋₁/Bₙ at z1 and z2 (downward_group),
// y3ₙ = Bₙ₊₁/Bₙ = (2n+1)/z − ρₙ, and Qₙ = (ψₙ/Bₙ)(z1) / (ψₙ/Bₙ)(z2) as a
// running product.  (Both bases satisfy the same recurrences, and the
// transfer of layered_terms.hpp holds for either.)  Q's factor
// ρₙ(z1) yₙ₋₁(z1) / (ρₙ(z2) yₙ₋₁(z2)) takes 1/ρₙ(z2) = (2n−1)/z2 − ρₙ₋₁(z2)
// and 1/yₙ₋₁(z2) = (2n+1)/z2 − yₙ(z2) as the passes formed them (the same
// operations, avoid_zero included): no division.
template <class Real>
struct ShellRecurrence {
  using C = Complex<Real>;
  ScaledInverseComplex<Real, C> over_in, over_out;  // k/z1, k/z2
  const StoredComplex<Real>* y_in;                  // yₙ(z1)
  const StoredComplex<Real>* y_out;                 // yₙ(z2)
  const StoredComplex<Real>* rho_in;                // ρₙ(z1), n = 0 .. N + 1
  const StoredComplex<Real>* rho_out;               // ρₙ(z2)
  C q;  // Qₙ₋₁ (before order 1: see shell_recurrence)

  // Orders first .. first + count − 1 into the block's entries 0 .. count − 1.
  // The state in locals: through `this`, every double stored into `s`
  // (which might alias it) forced a reload within the chain.
  void block(std::size_t first, std::size_t count, ShellInputs<Real>& s) {
    const ScaledInverseComplex<Real, C> oi = over_in, oo = over_out;
    const StoredComplex<Real>* const yin = y_in;
    const StoredComplex<Real>* const yout = y_out;
    const StoredComplex<Real>* const rin = rho_in;
    const StoredComplex<Real>* const rout = rho_out;
    C qn = q;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t n = first + i;
      const C ri(rin[n].real(), rin[n].imag()), ro(rout[n].real(), rout[n].imag());
      const C ro_prev(rout[n - 1].real(), rout[n - 1].imag());
      const C den_out = oo(index_real<Real>(2 * n - 1)) - ro_prev;  // 1/ρₙ(z2)
      C f = cmul(ri, den_out);
      if (n > 1) {
        const C yi(yin[n - 1].real(), yin[n - 1].imag()), yo(yout[n].real(), yout[n].imag());
        C inv_yo = oo(index_real<Real>(2 * n + 1)) - yo;  // 1/yₙ₋₁(z2)
        avoid_zero<C, Real>(inv_yo);
        f = cmul(f, cmul(yi, inv_yo));
      }
      qn = cmul(qn, f);
      const C y3i = oi(index_real<Real>(2 * n + 1)) - ri;
      const C y3o = oo(index_real<Real>(2 * n + 1)) - ro;
      s.y1i_re[i] = yin[n].real(), s.y1i_im[i] = yin[n].imag();
      s.y3i_re[i] = y3i.real(), s.y3i_im[i] = y3i.imag();
      s.y1o_re[i] = yout[n].real(), s.y1o_im[i] = yout[n].imag();
      s.y3o_re[i] = y3o.real(), s.y3o_im[i] = y3o.imag();
      s.q_re[i] = qn.real(), s.q_im[i] = qn.imag();
    }
    q = qn;
  }
};

// A layered sphere in the working type, as a view of the caller's arrays:
// x[l] for l < layers, and the index of layer l at m[l − 1] on a perfectly
// conducting core (which needs layers >= 2 here), at m[l] otherwise.
template <class Real>
struct LayeredProblem {
  const Real* x;
  const Complex<Real>* m;
  std::size_t layers;
  bool conducting_core;
  const Complex<Real>& index(std::size_t l) const { return m[conducting_core ? l - 1 : l]; }
  const Real& outer_x() const { return x[layers - 1]; }
};

// The per-thread scratch of one call, reused from call to call (a size
// distribution makes thousands of calls; allocating these each time was a
// tenth of a call at x = 1): the downward tables (yₙ for every complex
// argument, yₙ(x) and ρₙ(x) at the surface) and the per-shell state.
template <class Real>
struct LayeredWorkspace {
  // yₙ of every complex argument: [0] the core (absent on a conductor), then
  // z1, z2 per shell.  Held by pointer: the buffers do not move.
  std::vector<std::unique_ptr<Scratch<StoredComplex<Real>>>> y, rho;  // rho: shells' arguments only
  std::vector<StoredComplex<Real>*> y_data, rho_data;                // rho_data: nullptr for the core
  std::vector<SecondSolution<Real>> second;                          // per argument (shells')
  Scratch<Real> y_x;                   // yₙ(x) of the real x
  Scratch<StoredComplex<Real>> rho_x;  // ρₙ(x)
  std::vector<std::size_t> miller;
  std::vector<ScaledInverseComplex<Real, Complex<Real>>> over;  // k/z of every complex argument
  std::vector<ShellConstants<Real>> constants;
  std::vector<ShellRecurrence<Real>> recurrences;
  std::vector<ShellInputs<Real>> shell_in;
  TermInputs<Real> in;
  TermOutputs<Real> terms;
  Modes<Real> modes;
  void release_large() {
    constexpr std::size_t kKeep = std::size_t(8) << 20;
    for (auto* tables : {&y, &rho})
      for (auto& t : *tables)
        if (t->capacity_bytes() > kKeep) t->release();
    if (y_x.capacity_bytes() > kKeep) y_x.release();
    if (rho_x.capacity_bytes() > kKeep) rho_x.release();
  }
};

// The complex arguments' k/z: the core (absent on a conductor), then z1, z2
// of every shell.
template <class Real>
void layered_arguments(const LayeredProblem<Real>& p, std::vector<ScaledInverseComplex<Real, Complex<Real>>>& over) {
  over.clear();
  if (!p.conducting_core) over.emplace_back(p.x[0], p.index(0));
  for (std::size_t l = 1; l < p.layers; ++l) {
    over.emplace_back(p.x[l - 1], p.index(l));
    over.emplace_back(p.x[l], p.index(l));
  }
}

// Shell l's constants (κ, r, 1/r; layered_terms.hpp).
template <class Real>
ShellConstants<Real> shell_constants(const LayeredProblem<Real>& p, std::size_t l) {
  using C = Complex<Real>;
  const C mo = p.index(l);
  const bool conductor = l == 1 && p.conducting_core;
  C kappa(Real(0)), r(Real(1)), inv_r(Real(1));
  if (!conductor) {
    const C mi = p.index(l - 1);
    // (m_{l−1}² − m_l²)/(m_l m_{l−1}² x_{l−1}), the difference factored (trap contrast-near-1).
    kappa = cmul(cmul(C(mi - mo), C(mi + mo)), recip(C(cmul(cmul(mo, mi), mi) * p.x[l - 1])));
    r = cmul(mo, recip(mi));
    inv_r = cmul(mi, recip(mo));
  }
  return {kappa.real(), kappa.imag(), r.real(), r.imag(), inv_r.real(), inv_r.imag(), conductor,
          ScaledInverseComplex<Real, C>(p.x[l - 1], mo)};
}

// Whether shell l transfers in the basis (ψ, χ) (trap spurious-absorption).
template <class Real>
bool chi_basis(const LayeredProblem<Real>& p, std::size_t l) {
  return static_cast<double>(p.index(l).imag() * p.x[l]) <= kChiBasisMaxImZ;
}

// Shell l's upward pass before order 1 (arguments j, j + 1):
// Q₀ = [phase] (ψ₁/B₀)(z1) / (ψ₁/B₀)(z2), the phase e^{2i(z2−z1)} in the
// basis ξ (undoing the scale of hankel_solution).
template <class Real>
ShellRecurrence<Real> shell_recurrence(const LayeredProblem<Real>& p, std::size_t l, std::size_t j,
                                       const LayeredWorkspace<Real>& w) {
  using C = Complex<Real>;
  using W = typename WideOf<Real>::type;
  const C m = p.index(l);
  const StoredComplex<Real>*yi = w.y_data[j], *yo = w.y_data[j + 1];
  const C s_in = psi1_over_b0(w.second[j], C(yi[0].real(), yi[0].imag()), w.over[j](Real(1)));
  const C s_out = psi1_over_b0(w.second[j + 1], C(yo[0].real(), yo[0].imag()), w.over[j + 1](Real(1)));
  C q = cmul(s_in, recip(s_out));
  // e^{2i m_l (x_l − x_{l−1})} (trap thin-shell: the difference of two doubles, exact in W).
  if (!w.second[j].chi) q = cmul(twice_exp_minus_1<Real>(W(p.x[l]) - W(p.x[l - 1]), m) + C(Real(1)), q);
  return {w.over[j], w.over[j + 1], yi, yo, w.rho_data[j], w.rho_data[j + 1], q};
}

// Pass 1 at the surface (as block_inputs_for in series.hpp): Rₙ, sₙ, and
// yₙ(x), ρₙ(x) from their tables.
template <class Real>
void surface_inputs(std::size_t first, std::size_t count, const Real* y, const StoredComplex<Real>* rho_x,
                    Complex<Real>& R_io, Real& s_io, TermInputs<Real>& in) {
  using C = Complex<Real>;
  // The running state in locals (see ShellRecurrence::block).
  C R = R_io;
  Real s = s_io;
  Real sign = first % 2 == 0 ? Real(1) : Real(-1);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t n = first + i;
    const C rho(rho_x[n].real(), rho_x[n].imag());
    R = n == 1 ? cmul(R, rho) : cmul(R, rho) * y[n - 1];
    s *= norm2(rho);
    in.rn[i] = index_real<Real>(n);
    in.yx[i] = y[n];
    in.R_re[i] = R.real(), in.R_im[i] = R.imag();
    in.s[i] = s;
    in.rho_re[i] = rho.real(), in.rho_im[i] = rho.imag();
    in.sign[i] = sign;
    sign = -sign;
  }
  R_io = R, s_io = s;
}

// Pass 2 of a block: the modes from the core out through every shell, then
// the surface coefficients and the terms of the sums.
template <class Real>
void layered_block_terms(const LayeredProblem<Real>& p, LayeredWorkspace<Real>& w,
                         const SurfaceConstants<Real>& surface, std::size_t first, std::size_t count,
                         const Complex<Real>& a_prev, const Complex<Real>& b_prev) {
  Modes<Real>& y = w.modes;
  for (std::size_t i = 0; i < count; ++i) {
    if (p.conducting_core) {
      y.a_re[i] = y.a_im[i] = y.b_re[i] = y.b_im[i] = Real(0);
    } else {
      const StoredComplex<Real>& c = w.y_data[0][first + i];
      y.a_re[i] = y.b_re[i] = c.real(), y.a_im[i] = y.b_im[i] = c.imag();
    }
  }
  for (std::size_t l = 0; l < w.constants.size(); ++l) {
    if constexpr (std::is_same_v<Real, double>) shell_transfer_double(w.constants[l], w.shell_in[l], first, count, y);
    else shell_transfer(w.constants[l], w.shell_in[l], first, count, y);
  }
  if constexpr (std::is_same_v<Real, double>) {
    surface_terms_double(surface, w.in, y, count, w.terms);
    sum_terms_double(w.in, count, a_prev, b_prev, w.terms);
  } else {
    surface_terms(surface, w.in, y, count, w.terms);
    sum_terms(w.in, count, a_prev, b_prev, w.terms);
  }
}

// The surface constants of the outer layer.
template <class Real>
SurfaceConstants<Real> surface_constants(const LayeredProblem<Real>& p) {
  using C = Complex<Real>;
  const Real& x = p.outer_x();
  const C m = p.index(p.layers - 1);
  const C m2 = cmul(m, m);
  const C c = cmul(C(m - C(Real(1))) * C(m + C(Real(1))), recip(m));  // (m² − 1)/m, trap m-near-1
  return {m.real(), m.imag(), c.real(), c.imag(), m2.real(), m2.imag(), ScaledInverse<Real>(x),
          ScaledInverseComplex<Real, C>(x, m)};
}

// A table of at least n entries held by pointer (the buffers do not move).
template <class T>
T* table(std::vector<std::unique_ptr<Scratch<T>>>& tables, std::size_t j, std::size_t n) {
  while (tables.size() <= j) tables.push_back(std::make_unique<Scratch<T>>());
  tables[j]->resize(n);
  return &(*tables[j])[0];
}

// Fills the tables of every argument: yₙ for n = 0 .. N, and for the shells'
// arguments and the real x ρₙ for n = 0 .. N + 1.
template <class Real>
void layered_tables(const LayeredProblem<Real>& p, std::size_t N, LayeredWorkspace<Real>& w) {
  using C = Complex<Real>;
  const std::size_t count = w.over.size();
  w.y_data.assign(count, nullptr);
  w.rho_data.assign(count, nullptr);
  w.second.resize(count);
  w.miller.assign(count, 0);
  std::size_t j = 0;
  const auto argument = [&](const Real& x, const C& m, const SecondSolution<Real>* second) {
    w.y_data[j] = table<StoredComplex<Real>>(w.y, j, N + 1);
    if (second) {
      w.second[j] = *second;
      w.rho_data[j] = table<StoredComplex<Real>>(w.rho, j, N + 2);
      store(w.rho_data[j][0], second->rho0);
    }
    if constexpr (std::is_same_v<Real, double>) w.miller[j] = miller_depth(std::sqrt(norm2(m)) * x, 1.0, N);
    ++j;
  };
  if (!p.conducting_core) argument(p.x[0], p.index(0), nullptr);
  for (std::size_t l = 1; l < p.layers; ++l) {
    const C m = p.index(l);
    const bool chi = chi_basis(p, l);
    const SecondSolution<Real> in = chi ? neumann_solution(p.x[l - 1], m) : hankel_solution(p.x[l - 1], m);
    const SecondSolution<Real> out = chi ? neumann_solution(p.x[l], m) : hankel_solution(p.x[l], m);
    argument(p.x[l - 1], m, &in), argument(p.x[l], m, &out);
  }
  w.y_x.resize(N + 1);
  w.rho_x.resize(N + 2);
  const ScaledInverse<Real> over_x(p.outer_x());
  SurfaceChains<Real> surface{&over_x, 0, &w.y_x[0], &w.rho_x[0]};
  if constexpr (std::is_same_v<Real, double>) surface.miller = miller_depth(p.outer_x(), 1.0, N);
  downward_complex<Real>(surface, w.over, w.miller.data(), N, w.y_data.data(), w.rho_data.data());
}

// The shells' constants and recurrences before order 1.
template <class Real>
void layered_shells(const LayeredProblem<Real>& p, LayeredWorkspace<Real>& w) {
  const std::size_t shells = p.layers - 1;
  const std::size_t core = p.conducting_core ? 0 : 1;  // complex arguments before the shells'
  w.constants.clear();
  w.recurrences.clear();
  for (std::size_t l = 1; l <= shells; ++l) {
    const std::size_t j = core + 2 * (l - 1);
    w.constants.push_back(shell_constants(p, l));
    w.recurrences.push_back(shell_recurrence(p, l, j, w));
  }
  if (w.shell_in.size() < shells) w.shell_in.resize(shells);
}

// One summation of the series from tables of N + 1 entries into `out`;
// false if the converged rule asked for more than N terms.
template <class Real>
bool layered_sum(const LayeredProblem<Real>& p, const Extras& extras, bool converged_rule, std::size_t N,
                 Scattering<Real>& out) {
  using C = Complex<Real>;
  using std::cos;
  using std::sin;
  thread_local LayeredWorkspace<Real> w;
  struct Release {
    LayeredWorkspace<Real>& w;
    ~Release() { w.release_large(); }
  } release_large_tables{w};
  layered_arguments(p, w.over);
  layered_tables(p, N, w);
  layered_shells(p, w);
  const SurfaceConstants<Real> surface = surface_constants(p);

  const Real& x = p.outer_x();
  const double xd = static_cast<double>(x);
  out = Scattering<Real>{};
  const bool any_angle = !extras.angles_deg.empty();
  if (any_angle) out.angles_deg = extras.angles_deg;
  std::optional<AngularSums<Real>> angular;
  if (any_angle) angular.emplace(extras.angles_deg, out);
  const Real tol = series_tolerance<Real>();
  SeriesSums<Real> sums;
  VectorSums vector_sums;
  const Real sx = sin(x), cx = cos(x);
  const Real* yx = &w.y_x[0];
  const Real psi1 = riccati_psi1(sx, cx, yx[0], surface.over_x(Real(1)));
  C R(sx * psi1, cx * psi1);  // ψ₁/ξ₀; R₁ = ρ₁ ψ₁/ξ₀ (trap sin-zero)
  Real s(1);                  // 1/|ξ₀|²
  C a_prev(Real(0)), b_prev(Real(0));
  bool converged = !converged_rule, stopped = false;
  std::size_t n_last = N;
  std::size_t block = kFirstTermBlock;
  for (std::size_t first = 1, count = 0; first <= N && !stopped; first += count, block = kTermBlock) {
    count = std::min(block, N + 1 - first);
    // Pass 1 (serial): the upward recurrences.
    surface_inputs(first, count, yx, &w.rho_x[0], R, s, w.in);
    for (std::size_t l = 0; l < w.recurrences.size(); ++l) w.recurrences[l].block(first, count, w.shell_in[l]);
    // Pass 2 (every order independently).
    layered_block_terms(p, w, surface, first, count, a_prev, b_prev);
    // Pass 3 (serial).
    const BlockSum summed = sum_block<Real>(w.terms, first, count, xd, tol, converged_rule, sums, vector_sums);
    if (summed.stopped) {
      converged = stopped = true;
      n_last = first + summed.used - 1;
    }
    add_extras(extras, first, summed.used, w.terms, angular, out);
    a_prev = C(w.terms.a_re[count - 1], w.terms.a_im[count - 1]);
    b_prev = C(w.terms.b_re[count - 1], w.terms.b_im[count - 1]);
  }
  if constexpr (std::is_same_v<Real, double>) vector_sums.to(sums);
  if (any_angle) angular->finish();
  sums.finish(x, false, n_last, out.q);
  return converged;
}

// The series of a layered sphere (layers >= 1; >= 2 on a conductor), with
// the term rule of `options` (the converged rule first tries first_terms of
// the outer x, then max_terms, as mie_series does).
template <class Real>
Scattering<Real> layered_series(const LayeredProblem<Real>& p, const Extras& extras, const Options& options) {
  const double x = static_cast<double>(p.outer_x());
  const bool converged_rule = options.terms == TermRule::converged;
  const double cbrt_x = bound_cbrt(x);
  const std::size_t n_max =
      converged_rule ? max_terms<Real>(x, cbrt_x) : std::max<std::size_t>(1, wiscombe_term_count(x));
  std::size_t N = converged_rule ? first_terms<Real>(x, cbrt_x) : n_max;
  Scattering<Real> out;
  while (!layered_sum<Real>(p, extras, converged_rule, N, out) && N < n_max) N = n_max;
  return out;
}

}  // namespace attenuvis::mie::detail
