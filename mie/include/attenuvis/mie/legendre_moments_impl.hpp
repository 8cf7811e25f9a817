// Expansion of a sphere's scattering matrix in Legendre polynomials / Wigner
// d-functions, from its Mie coefficients aₙ, bₙ; templated on the floating type.
//
// Template detail of attenuvis/mie/legendre_moments.hpp, included only by
// mie/src/legendre_moments.cpp (double) and mie/src/legendre_moments_referee.cpp
// (50-digit referee), so that both run exactly the same algorithm.
//
// Method.  With a series of N terms, S1(μ) and S2(μ) are polynomials of degree N in
// μ = cos θ (πₙ has degree n−1, τₙ degree n), so every product |S1|², |S2|²,
// S2 S1*, |S1 ± S2|² has degree <= 2N, and the Wigner functions d^l_{00} = P_l,
// d^l_{22}, d^l_{2,−2}, d^l_{02} are polynomials of degree l.  A Gauss–Legendre
// rule of order n_q integrates degree 2n_q − 1 exactly, so n_q = N + ⌈(L+1)/2⌉
// (2N + 1 for L = 2N) gives every coefficient up to l = L with no quadrature
// error at all: what remains is rounding.  This is the approach of Evans' MIEWIG
// (SHDOM) and of de Rooij & van der Stap (1984, A&A 131:237, §3), and avoids the
// double sums over n, n' per moment of Dave (1970), which MIEV0's LPCOEF
// (Wiscombe 1979) evaluates for the first NMOM moments.
//
// Cost O(N·n_q + L·n_q) = O(N²).  Both loops use the parity of the angular
// functions (πₙ(−μ) = (−1)^{n−1} πₙ(μ), τₙ(−μ) = (−1)ⁿ τₙ(μ), P_l(−μ) = (−1)^l P_l,
// d^l_{22}(−μ) = (−1)^l d^l_{2,−2}(μ), d^l_{02}(−μ) = (−1)^l d^l_{02}(μ)), so only
// the nodes with μ >= 0 are visited.
//
// Accuracy near θ = 0 (the forward peak, which carries half of the scattering of
// a large sphere in a cone Δθ ≈ 1/x):
//   * the nodes are held as s = sin²(θ/2) (gauss_legendre.hpp), every μ·v is
//     formed as v − 2s·v;
//   * the forward recurrences for πₙ, τₙ (B&H 4.47), P_l and d^l_{22}, whose
//     rounding grows like n·ε near μ = 1 (measured 2e-13 in χ₀ at x = 1000 with
//     the plain recurrences), run there (s <= ¼) on differences of consecutive terms
//     (Reinsch's modification), which keeps the error at a few ε; and τₙ is
//     formed from those differences rather than as nμπₙ − (n+1)πₙ₋₁, which near
//     μ = 1 subtracts terms ~n³/2 to leave ~n²/2 (amplitude_chunk below).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/gauss_legendre.hpp"
#include "attenuvis/mie/legendre_moments.hpp"

namespace attenuvis::mie::detail {

// Rule of at least `order` nodes, cached per thread: building one costs O(n²)
// (gauss_legendre.hpp), as much as the moments themselves, and neighbouring
// spheres of a size distribution need nearly the same order.  Any order >= the
// one needed is exact, so the order is rounded up to a multiple of about 1/32
// to 1/16 of itself and a rule is reused across that bin.  The rounding
// depends on `order` alone, never on which spheres a thread saw before, so a
// sphere's moments are the same bits whatever the threads and their history.
inline std::size_t binned_rule_order(std::size_t order) {
  std::size_t top = 1;
  while (top * 2 <= order) top *= 2;
  const std::size_t q = top >= 64 ? top / 32 : 1;
  return (order + q - 1) / q * q + 1;
}

template <class Real>
const HalfGaussLegendre<Real>& cached_rule(std::size_t order) {
  thread_local HalfGaussLegendre<Real> rule;
  const std::size_t binned = binned_rule_order(order);
  if (rule.order != binned) rule = half_gauss_legendre<Real>(binned);
  return rule;
}

// Products of the amplitude functions at ±μ of each half-rule node, divided by
// W = Σ (2n+1)(|aₙ|² + |bₙ|²) = x² Qsca / 2 (then a1 = (|S1|²+|S2|²)/W is the
// phase function with ½∫a1 dμ = 1), and multiplied by the node's weight.
template <class Real>
struct WeightedProducts {
  // index [0] at +μ, [1] at −μ
  std::array<std::vector<Real>, 2> a1;      // (|S1|² + |S2|²)/W   = p
  std::array<std::vector<Real>, 2> a3;      // 2 Re(S2 S1*)/W      (= a4 for spheres)
  std::array<std::vector<Real>, 2> sum;     // |S1 + S2|²/W = a2 + a3
  std::array<std::vector<Real>, 2> diff;    // |S1 − S2|²/W = a2 − a3
  std::array<std::vector<Real>, 2> b1;      // (|S2|² − |S1|²)/W
  std::array<std::vector<Real>, 2> b2;      // −2 Im(S2 S1*)/W  (sign: see legendre_moments.hpp)
};

template <class Real>
Real scattering_norm(const std::vector<Complex<Real>>& a, const std::vector<Complex<Real>>& b) {
  Real w = 0;
  for (std::size_t i = a.size(); i-- > 0;) {  // small terms first
    const Real n = Real(i + 1);
    w += (2 * n + 1) * (a[i].real() * a[i].real() + a[i].imag() * a[i].imag() +
                         b[i].real() * b[i].real() + b[i].imag() * b[i].imag());
  }
  return w;
}

// The Mie coefficients arranged for the node loop: per n the coefficients of the
// even and odd parts (in μ) of S1; S2's are the same pair swapped.  n odd: uₙ is
// even in μ and tₙ odd (πₙ(−μ) = (−1)^{n−1} πₙ(μ), τₙ(−μ) = (−1)ⁿ τₙ(μ)); n even:
// the reverse.  With S1 = Σ (2n+1)/2 (aₙuₙ + bₙtₙ), S2 = Σ (2n+1)/2 (aₙtₙ + bₙuₙ):
//   n odd:  S1 even part += A·u, odd part += B·t;  S2 even += B·u, odd += A·t,
//   n even: S1 even part += B·t, odd part += A·u;  S2 even += A·t, odd += B·u,
// i.e. S1_even += P·ev, S1_odd += Q·od, S2_even += Q·ev, S2_odd += P·od with
// (ev, od) = (u, t), (P, Q) = (A, B) for odd n and (ev, od) = (t, u), (P, Q) = (B, A)
// for even n; A, B = (2n+1)/2 · aₙ, bₙ.
template <class Real>
struct AmplitudeSeries {
  std::vector<Real> pr, pi, qr, qi, k_prev, k_cur;  // index n−1
  AmplitudeSeries(const std::vector<Complex<Real>>& a, const std::vector<Complex<Real>>& b)
      : pr(a.size()), pi(a.size()), qr(a.size()), qi(a.size()), k_prev(a.size()), k_cur(a.size()) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::size_t n = i + 1;
      const Real f = Real(2 * n + 1) / 2;
      const Complex<Real>& p = n % 2 ? a[i] : b[i];
      const Complex<Real>& q = n % 2 ? b[i] : a[i];
      pr[i] = f * p.real();
      pi[i] = f * p.imag();
      qr[i] = f * q.real();
      qi[i] = f * q.imag();
      k_prev[i] = Real(n - 1) / Real(n + 2);
      k_cur[i] = Real(2 * n + 1) / Real(n + 2);
    }
  }
};

inline constexpr std::size_t kChunk = 32;

// S1, S2 (even and odd parts) at `len` <= kChunk consecutive nodes, added to out[k][j0 + j].
// The angular functions are carried normalised to 1 at μ = 1:
//   uₙ = πₙ/cₙ,  tₙ = τₙ/cₙ,  cₙ = n(n+1)/2 = πₙ(1) = τₙ(1).  From B&H 4.47:
//   (n+2) uₙ₊₁ = (2n+1) μ uₙ − (n−1) uₙ₋₁,      tₙ = n μ uₙ − (n−1) uₙ₋₁.
// Near μ = 1 both lose ~log₁₀ n digits (the terms are ~n times the result, and the
// rounding of the forward recurrence grows like n·ε: 2e-13 in χ₀ at x = 1000);
// there (NearForward: s <= ¼) they run on the differences Eₙ = uₙ − uₙ₋₁ instead
// (Reinsch's modification):
//   Eₙ₊₁ = ((n−1) Eₙ − 2s (2n+1) uₙ)/(n+2),  uₙ₊₁ = uₙ + Eₙ₊₁,
//   tₙ = uₙ₋₁ + n (Eₙ − 2s uₙ),
// obtained by subtracting the μ = 1 identity (n+2) = (2n+1) − (n−1).
template <class Real, bool NearForward>
void amplitude_chunk(const AmplitudeSeries<Real>& c, const Real* two_s, std::size_t len, Real* const out[8],
                     std::size_t j0) {
  Real ts[kChunk], u0[kChunk], u1[kChunk], e[kChunk];
  Real s1e_r[kChunk], s1e_i[kChunk], s1o_r[kChunk], s1o_i[kChunk];
  Real s2e_r[kChunk], s2e_i[kChunk], s2o_r[kChunk], s2o_i[kChunk];
  for (std::size_t j = 0; j < kChunk; ++j) {
    ts[j] = j < len ? two_s[j] : Real(0);
    u0[j] = 1;  // u₀ is arbitrary (its coefficient is zero); 1 makes E₁ = 0
    u1[j] = 1;
    e[j] = 0;
    s1e_r[j] = s1e_i[j] = s1o_r[j] = s1o_i[j] = s2e_r[j] = s2e_i[j] = s2o_r[j] = s2o_i[j] = Real(0);
  }
  const std::size_t nt = c.pr.size();
  for (std::size_t i = 0; i < nt; ++i) {
    const bool odd = i % 2 == 0;  // n = i+1
    const Real pr = c.pr[i], pi = c.pi[i], qr = c.qr[i], qi = c.qi[i];
    const Real rn = Real(i + 1), rn1 = Real(i), kp = c.k_prev[i], kc = c.k_cur[i];
    for (std::size_t j = 0; j < kChunk; ++j) {
      const Real u = u1[j];
      Real t;
      if constexpr (NearForward) {
        t = u0[j] + rn * (e[j] - ts[j] * u);
        e[j] = kp * e[j] - kc * ts[j] * u;
        u0[j] = u;
        u1[j] = u + e[j];
      } else {
        const Real mu_u = u - ts[j] * u;
        t = rn * mu_u - rn1 * u0[j];
        u1[j] = kc * mu_u - kp * u0[j];
        u0[j] = u;
      }
      const Real ev = odd ? u : t, od = odd ? t : u;
      s1e_r[j] += pr * ev;
      s1e_i[j] += pi * ev;
      s1o_r[j] += qr * od;
      s1o_i[j] += qi * od;
      s2e_r[j] += qr * ev;
      s2e_i[j] += qi * ev;
      s2o_r[j] += pr * od;
      s2o_i[j] += pi * od;
    }
  }
  for (std::size_t j = 0; j < len; ++j) {
    out[0][j0 + j] = s1e_r[j];
    out[1][j0 + j] = s1e_i[j];
    out[2][j0 + j] = s1o_r[j];
    out[3][j0 + j] = s1o_i[j];
    out[4][j0 + j] = s2e_r[j];
    out[5][j0 + j] = s2e_i[j];
    out[6][j0 + j] = s2o_r[j];
    out[7][j0 + j] = s2o_i[j];
  }
}

template <class Real>
WeightedProducts<Real> weighted_products(const std::vector<Complex<Real>>& a,
                                         const std::vector<Complex<Real>>& b,
                                         const HalfGaussLegendre<Real>& rule, bool full_matrix) {
  const std::size_t m = rule.s.size();
  AmplitudeSeries<Real> c(a, b);
  std::vector<Real> e1r(m), e1i(m), o1r(m), o1i(m), e2r(m), e2i(m), o2r(m), o2i(m), two_s(m);
  std::size_t split = 0;  // nodes [0, split) have s <= 1/4 (ascending s)
  for (std::size_t j = 0; j < m; ++j) {
    two_s[j] = 2 * rule.s[j];
    if (rule.s[j] <= Real(0.25)) split = j + 1;
  }
  // Chunks of nodes small enough for the per-node state to stay in L1 (and, for
  // double, to let the compiler vectorise across nodes without aliasing doubts).
  Real* const parts[8] = {e1r.data(), e1i.data(), o1r.data(), o1i.data(),
                          e2r.data(), e2i.data(), o2r.data(), o2i.data()};
  for (std::size_t j0 = 0; j0 < m;) {
    const bool near = j0 < split;
    const std::size_t len = std::min(kChunk, (near ? split : m) - j0);
    if (near)
      amplitude_chunk<Real, true>(c, two_s.data() + j0, len, parts, j0);
    else
      amplitude_chunk<Real, false>(c, two_s.data() + j0, len, parts, j0);
    j0 += len;
  }
  const Real inv_w = 1 / scattering_norm<Real>(a, b);
  WeightedProducts<Real> out;
  for (int side = 0; side < 2; ++side) {
    out.a1[side].resize(m);
    if (full_matrix) {
      out.a3[side].resize(m);
      out.sum[side].resize(m);
      out.diff[side].resize(m);
      out.b1[side].resize(m);
      out.b2[side].resize(m);
    }
  }
  for (std::size_t j = 0; j < m; ++j) {
    const Real ww = rule.w[j] * inv_w;
    for (int side = 0; side < 2; ++side) {
      const Real sg = side == 0 ? Real(1) : Real(-1);
      const Real s1r = e1r[j] + sg * o1r[j], s1i = e1i[j] + sg * o1i[j];
      const Real s2r = e2r[j] + sg * o2r[j], s2i = e2i[j] + sg * o2i[j];
      const Real i1 = s1r * s1r + s1i * s1i, i2 = s2r * s2r + s2i * s2i;
      out.a1[side][j] = ww * (i1 + i2);
      if (!full_matrix) continue;
      const Real re = s2r * s1r + s2i * s1i, im = s2i * s1r - s2r * s1i;
      out.a3[side][j] = ww * 2 * re;
      out.sum[side][j] = ww * ((s1r + s2r) * (s1r + s2r) + (s1i + s2i) * (s1i + s2i));
      out.diff[side][j] = ww * ((s1r - s2r) * (s1r - s2r) + (s1i - s2i) * (s1i - s2i));
      out.b1[side][j] = ww * (i2 - i1);
      out.b2[side][j] = ww * (-2 * im);
    }
  }
  return out;
}

// Length of the result: up to 2N, or to max_l when the caller asked for more
// (all_orders means "up to 2N").
inline std::size_t output_length(std::size_t terms, std::size_t max_l) {
  return (max_l == all_orders ? 2 * terms : max_l) + 1;
}

// Number of nodes needed for exact coefficients up to l = max_l with N terms.
inline std::size_t exact_order(std::size_t terms, std::size_t max_l) { return terms + (max_l + 2) / 2; }

// Σ_j f[j]·g[j] with four partial sums (independent additions vectorise).
template <class Real>
Real dot4(const std::vector<Real>& f, const std::vector<Real>& g) {
  std::array<Real, 4> acc{Real(0), Real(0), Real(0), Real(0)};
  const std::size_t m = f.size();
  std::size_t j = 0;
  for (; j + 4 <= m; j += 4)
    for (std::size_t q = 0; q < 4; ++q) acc[q] += f[j + q] * g[j + q];
  for (; j < m; ++j) acc[0] += f[j] * g[j];
  return (acc[0] + acc[1]) + (acc[2] + acc[3]);
}

// P_l at every node of a half rule, one degree at a time: Bonnet's recurrence,
// for s <= ¼ in the difference form Dₗ₊₁ = (l Dₗ − 2s(2l+1) Pₗ)/(l+1),
// Pₗ₊₁ = Pₗ + Dₗ₊₁ (see weighted_products and gauss_legendre.hpp for why).
template <class Real>
struct LegendreSweep {
  std::vector<Real> p0, p1, d, two_s;  // P_l, P_{l+1}, P_{l+1} − P_l
  std::size_t split = 0;               // nodes [0, split) have s <= ¼

  explicit LegendreSweep(const HalfGaussLegendre<Real>& rule)
      : p0(rule.s.size(), Real(1)), p1(rule.s.size()), d(rule.s.size()), two_s(rule.s.size()) {
    for (std::size_t j = 0; j < rule.s.size(); ++j) {
      two_s[j] = 2 * rule.s[j];
      p1[j] = 1 - two_s[j];
      d[j] = -two_s[j];
      if (rule.s[j] <= Real(0.25)) split = j + 1;
    }
  }
  // On entry p0 = P_l; on exit p0 = P_{l+1}.
  void advance(std::size_t l) {
    const Real k1 = Real(2 * l + 3) / Real(l + 2), k2 = Real(l + 1) / Real(l + 2);
    for (std::size_t j = 0; j < split; ++j) {
      const Real nd = k2 * d[j] - k1 * two_s[j] * p1[j];
      p0[j] = p1[j];
      p1[j] += nd;
      d[j] = nd;
    }
    for (std::size_t j = split; j < p0.size(); ++j) {
      const Real next = k1 * (p1[j] - two_s[j] * p1[j]) - k2 * p0[j];
      p0[j] = p1[j];
      p1[j] = next;
    }
  }
};

// χ_l = ½ ∫ p P_l dμ for l = 0..max_l (entries above 2N are exactly zero).
template <class Real>
std::vector<Real> legendre_moments(const std::vector<Complex<Real>>& a, const std::vector<Complex<Real>>& b,
                                   std::size_t max_l) {
  if (a.empty() || a.size() != b.size())
    throw std::invalid_argument(
        "Legendre moments need the Mie coefficients: call scatter() with extras.coefficients = true");
  const std::size_t nt = a.size(), lmax = std::min(max_l, 2 * nt);
  const HalfGaussLegendre<Real>& rule = cached_rule<Real>(exact_order(nt, lmax));
  const WeightedProducts<Real> f = weighted_products<Real>(a, b, rule, false);
  const std::size_t m = rule.s.size();
  std::vector<Real> even(m), odd(m);
  for (std::size_t j = 0; j < m; ++j) {
    even[j] = (f.a1[0][j] + f.a1[1][j]) / 2;
    odd[j] = (f.a1[0][j] - f.a1[1][j]) / 2;
  }
  std::vector<Real> chi(output_length(nt, max_l), Real(0));
  LegendreSweep<Real> p(rule);
  for (std::size_t l = 0; l <= lmax; ++l) {
    chi[l] = dot4(l % 2 == 0 ? even : odd, p.p0);
    p.advance(l);
  }
  return chi;
}

}  // namespace attenuvis::mie::detail

#include "attenuvis/mie/gsf_coefficients_impl.hpp"
