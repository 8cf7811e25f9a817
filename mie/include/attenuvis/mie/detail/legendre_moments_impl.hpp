// Expansion of a sphere's scattering matrix in Legendre polynomials / Wigner
// d-functions, from its Mie coefficients aₙ, bₙ; templated on the floating type.
//
// Template detail of attenuvis/mie/legendre_moments.hpp, instantiated by
// mie/src/legendre_moments.cpp (double; its node loops compiled per instruction
// set in legendre_moments_double.cpp) and mie/src/legendre_moments_referee.cpp
// (50-digit referee), so that both run exactly the same algorithm.  Tests and
// the moments benchmark also run it in long double, and in double without the
// per-instruction-set loops (PerIsa = false).
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
// the nodes with μ >= 0 are visited.  They run chunk by chunk of nodes: S1, S2
// at kChunk nodes, their products, then every degree l for those nodes, so that
// all of it stays in L1 and the nodes of a chunk form the vector lanes (in
// double, one clone per instruction set: mie/src/legendre_moments_double.cpp).
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
#include <map>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/detail/gauss_legendre.hpp"
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

//
// Every binned order a thread meets is kept (a map, whose entries stay put), not
// only the last one: the nodes of a size-distribution quadrature panel visit
// sizes in the order of the Kronrod abscissae, so consecutive spheres alternate
// between bins, and with a single cached rule more than half of the time of
// `attenuvis optics … --moments 64` went into rebuilding rules.  ~32 bins per
// octave of order, a rule of order n holding 8n bytes in double, is ~800·n_max
// bytes for all orders up to n_max (1.7 MB at x = 1000, L = 2N); past
// kMaxCachedNodes summed orders (8 MB in double per thread) the cache starts
// afresh, which changes only the time, never a result.
inline constexpr std::size_t kMaxCachedNodes = std::size_t(1) << 20;

template <class Real>
const HalfGaussLegendre<Real>& cached_rule(std::size_t order) {
  thread_local std::map<std::size_t, HalfGaussLegendre<Real>> rules;
  thread_local std::size_t cached_nodes = 0;
  const std::size_t binned = binned_rule_order(order);
  const auto found = rules.find(binned);
  if (found != rules.end()) return found->second;
  if (cached_nodes + binned > kMaxCachedNodes) {
    rules.clear();
    cached_nodes = 0;
  }
  cached_nodes += binned;
  return rules.emplace(binned, half_gauss_legendre<Real>(binned)).first->second;
}

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

// The node loops run on blocks of kLanes nodes: the state of one block (four
// recurrence values and eight partial sums per node) then fits the vector
// registers of AVX-512 (12 of 32) and nearly those of AVX2, instead of going
// through memory for every term.  The moments are accumulated over chunks of
// kChunk nodes (moments_chunk).  Neither size changes any result of a node,
// and the chunk sums are formed in an order fixed by kLanes and kChunk alone,
// so the results do not depend on the instruction set either.
inline constexpr std::size_t kLanes = 8;
inline constexpr std::size_t kChunk = 32;

// The nodes of the half-range rule as the chunk kernels read them: 2sⱼ, the
// weights wⱼ divided by the norm W of the phase function, and how many nodes
// (ascending s) have s <= ¼ and so take the near-forward (difference) form of
// the recurrences.  Shared by the moments of p(μ) and the expansion of the
// whole scattering matrix, which sum over the same nodes.
template <class Real>
struct WeightedNodes {
  std::vector<Real> two_s, weight;
  std::size_t split = 0;  // nodes [0, split) have s <= ¼
  WeightedNodes(const HalfGaussLegendre<Real>& rule, const Real& inv_w)
      : two_s(rule.s.size()), weight(rule.s.size()) {
    for (std::size_t j = 0; j < rule.s.size(); ++j) {
      two_s[j] = 2 * rule.s[j];
      weight[j] = rule.w[j] * inv_w;
      if (rule.s[j] <= Real(0.25)) split = j + 1;
    }
  }
  // f(two_s, weight, len, near) for chunks of at most kChunk nodes, none of
  // which straddles s = ¼.
  template <class F>
  void for_each_chunk(const F& f) const {
    const std::size_t m = two_s.size();
    for (std::size_t j0 = 0; j0 < m;) {
      const bool near = j0 < split;
      const std::size_t len = std::min(kChunk, (near ? split : m) - j0);
      f(two_s.data() + j0, weight.data() + j0, len, near);
      j0 += len;
    }
  }
};

// The kernels are inlined into their per-instruction-set callers
// (mie/src/legendre_moments_double.cpp), which is what compiles them for each set.
#if defined(__GNUC__)
#define ATTENUVIS_MIE_KERNEL __attribute__((always_inline)) inline
#else
#define ATTENUVIS_MIE_KERNEL inline
#endif

// S1, S2 (even and odd parts) at kLanes nodes, one series term at a time.
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
template <class Real>
struct AmplitudeBlock {
  Real ts[kLanes], u0[kLanes], u1[kLanes], e[kLanes];
  Real s1e_r[kLanes], s1e_i[kLanes], s1o_r[kLanes], s1o_i[kLanes];
  Real s2e_r[kLanes], s2e_i[kLanes], s2o_r[kLanes], s2o_i[kLanes];

  AmplitudeBlock(const Real* two_s, std::size_t len) {
    for (std::size_t j = 0; j < kLanes; ++j) {
      ts[j] = j < len ? two_s[j] : Real(0);
      u0[j] = 1;  // u₀ is arbitrary (its coefficient is zero); 1 makes E₁ = 0
      u1[j] = 1;
      e[j] = 0;
      s1e_r[j] = s1e_i[j] = s1o_r[j] = s1o_i[j] = s2e_r[j] = s2e_i[j] = s2o_r[j] = s2o_i[j] = Real(0);
    }
  }

  // Term n = i + 1 (OddN: n odd, see AmplitudeSeries for the even/odd split);
  // odd and even n are separate instances so that the loop over the nodes has
  // no selection in it.
  template <bool NearForward, bool OddN>
  ATTENUVIS_MIE_KERNEL void term(const AmplitudeSeries<Real>& c, std::size_t i) {
    const Real pr = c.pr[i], pi = c.pi[i], qr = c.qr[i], qi = c.qi[i];
    const Real rn = Real(i + 1), rn1 = Real(i), kp = c.k_prev[i], kc = c.k_cur[i];
    for (std::size_t j = 0; j < kLanes; ++j) {
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
      const Real ev = OddN ? u : t, od = OddN ? t : u;
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

  template <bool NearForward>
  ATTENUVIS_MIE_KERNEL void sum(const AmplitudeSeries<Real>& c) {
    const std::size_t nt = c.pr.size();
    std::size_t i = 0;
    for (; i + 1 < nt; i += 2) {
      term<NearForward, true>(c, i);
      term<NearForward, false>(c, i + 1);
    }
    if (i < nt) term<NearForward, true>(c, i);
  }
};

// S1, S2 (even and odd parts) at `count` consecutive nodes 2s = two_s[j], all on
// one side of s = ¼ (`near`: s <= ¼), stored to out[k][j].
template <class Real>
ATTENUVIS_MIE_KERNEL void amplitudes(const AmplitudeSeries<Real>& c, const Real* two_s, std::size_t count,
                                     bool near, Real* const out[8]) {
  for (std::size_t j0 = 0; j0 < count; j0 += kLanes) {
    const std::size_t len = std::min(kLanes, count - j0);
    AmplitudeBlock<Real> b(two_s + j0, len);
    if (near)
      b.template sum<true>(c);
    else
      b.template sum<false>(c);
    for (std::size_t j = 0; j < len; ++j) {
      out[0][j0 + j] = b.s1e_r[j];
      out[1][j0 + j] = b.s1e_i[j];
      out[2][j0 + j] = b.s1o_r[j];
      out[3][j0 + j] = b.s1o_i[j];
      out[4][j0 + j] = b.s2e_r[j];
      out[5][j0 + j] = b.s2e_i[j];
      out[6][j0 + j] = b.s2o_r[j];
      out[7][j0 + j] = b.s2o_i[j];
    }
  }
}

// Bonnet's recurrence (l+2)P_{l+2} = (2l+3)μP_{l+1} − (l+1)P_l as
// P_{l+2} = k1[l] μP_{l+1} − k2[l] P_l, for l = 0..lmax.
template <class Real>
struct BonnetCoefficients {
  std::vector<Real> k1, k2;
  explicit BonnetCoefficients(std::size_t lmax) : k1(lmax + 1), k2(lmax + 1) {
    for (std::size_t l = 0; l <= lmax; ++l) {
      k1[l] = Real(2 * l + 3) / Real(l + 2);
      k2[l] = Real(l + 1) / Real(l + 2);
    }
  }
};

// One step of Bonnet's recurrence at a chunk's nodes: (p0, p1) = (P_l, P_{l+1})
// becomes (P_{l+1}, P_{l+2}), μ·v formed as v − 2s·v (ts = 2s).  NearForward
// (s <= ¼): on the differences d = P_{l+1} − P_l instead (Reinsch), whose
// rounding does not grow like l·ε near μ = 1: subtracting the μ = 1 identity
// k1 − k2 = 1 gives d_{l+2} = k2 d_{l+1} − k1 2s P_{l+1}.
template <class Real, bool NearForward>
ATTENUVIS_MIE_KERNEL void bonnet_step(Real k1, Real k2, const Real* ts, Real* p0, Real* p1, Real* d) {
  for (std::size_t j = 0; j < kChunk; ++j) {
    if constexpr (NearForward) {
      const Real nd = k2 * d[j] - k1 * ts[j] * p1[j];
      p0[j] = p1[j];
      p1[j] += nd;
      d[j] = nd;
    } else {
      const Real next = k1 * (p1[j] - ts[j] * p1[j]) - k2 * p0[j];
      p0[j] = p1[j];
      p1[j] = next;
    }
  }
}

// acc[k] += Σ_q f[q·kLanes + k] g[q·kLanes + k] over one chunk: kLanes running
// sums per moment, added up at the end (lane_total) — the same additions in the
// same order whatever the vector width, and no reduction across lanes per chunk.
template <class Real>
ATTENUVIS_MIE_KERNEL void accumulate_chunk(const Real* f, const Real* g, Real* acc) {
  for (std::size_t q = 0; q < kChunk; q += kLanes)
    for (std::size_t k = 0; k < kLanes; ++k) acc[k] += f[q + k] * g[q + k];
}

// acc[k] += Σ_q f[q·kLanes + k], in the same order.
template <class Real>
ATTENUVIS_MIE_KERNEL void accumulate_chunk_sum(const Real* f, Real* acc) {
  for (std::size_t q = 0; q < kChunk; q += kLanes)
    for (std::size_t k = 0; k < kLanes; ++k) acc[k] += f[q + k];
}

template <class Real>
Real lane_total(const Real* acc) {
  static_assert(kLanes == 8, "lane_total adds eight running sums");
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

// Adds to acc[l·kLanes + k] (l = 0..lmax) the share ½ Σ w p(±μ) P_l(±μ) of `len` <= kChunk nodes,
// all on one side of s = ¼ (NearForward: s <= ¼), with weight[j] = w_j / W.
// The phase function at ±μ is split into its even and odd parts, which P_l of
// even and odd l pick out; P_l runs by Bonnet's recurrence, for s <= ¼ in the
// difference form Dₗ₊₁ = (l Dₗ − 2s(2l+1) Pₗ)/(l+1), Pₗ₊₁ = Pₗ + Dₗ₊₁ (see
// gauss_legendre.hpp for why).  All of it stays in L1 for one chunk.
template <class Real, bool NearForward>
ATTENUVIS_MIE_KERNEL void moments_chunk(const AmplitudeSeries<Real>& c, const BonnetCoefficients<Real>& k,
                                        const Real* two_s, const Real* weight, std::size_t len, std::size_t lmax,
                                        Real* acc) {
  Real e1r[kChunk], e1i[kChunk], o1r[kChunk], o1i[kChunk], e2r[kChunk], e2i[kChunk], o2r[kChunk], o2i[kChunk];
  Real* const parts[8] = {e1r, e1i, o1r, o1i, e2r, e2i, o2r, o2i};
  amplitudes(c, two_s, len, NearForward, parts);
  Real even[kChunk], odd[kChunk], ts[kChunk], p0[kChunk], p1[kChunk], d[kChunk];
  for (std::size_t j = 0; j < kChunk; ++j) {
    even[j] = odd[j] = ts[j] = Real(0);  // the unused nodes weigh nothing
    if (j < len) {
      const Real ww = weight[j];
      ts[j] = two_s[j];
      Real at[2];
      for (int side = 0; side < 2; ++side) {
        const Real s1r = side == 0 ? e1r[j] + o1r[j] : e1r[j] - o1r[j];
        const Real s1i = side == 0 ? e1i[j] + o1i[j] : e1i[j] - o1i[j];
        const Real s2r = side == 0 ? e2r[j] + o2r[j] : e2r[j] - o2r[j];
        const Real s2i = side == 0 ? e2i[j] + o2i[j] : e2i[j] - o2i[j];
        at[side] = ww * ((s1r * s1r + s1i * s1i) + (s2r * s2r + s2i * s2i));
      }
      even[j] = (at[0] + at[1]) / 2;
      odd[j] = (at[0] - at[1]) / 2;
    }
    p0[j] = 1;
    p1[j] = 1 - ts[j];
    d[j] = -ts[j];
  }
  for (std::size_t l = 0; l <= lmax; ++l) {
    accumulate_chunk(l % 2 == 0 ? even : odd, p0, acc + l * kLanes);
    bonnet_step<Real, NearForward>(k.k1[l], k.k2[l], ts, p0, p1, d);
  }
}

// The double instance, compiled once per instruction set with run-time choice
// (mie/src/legendre_moments_double.cpp).
void moments_chunk_double(const AmplitudeSeries<double>& c, const BonnetCoefficients<double>& k,
                          const double* two_s, const double* weight, std::size_t len, bool near, std::size_t lmax,
                          double* acc);

// PerIsa: for double, the per-instruction-set instance (the same operations);
// otherwise, and for wider types, the kernel as compiled here.
template <class Real, bool PerIsa>
void moments_chunk_any(const AmplitudeSeries<Real>& c, const BonnetCoefficients<Real>& k, const Real* two_s,
                       const Real* weight, std::size_t len, bool near, std::size_t lmax, Real* acc) {
  if constexpr (PerIsa && std::is_same_v<Real, double>)
    moments_chunk_double(c, k, two_s, weight, len, near, lmax, acc);
  else if (near)
    moments_chunk<Real, true>(c, k, two_s, weight, len, lmax, acc);
  else
    moments_chunk<Real, false>(c, k, two_s, weight, len, lmax, acc);
}

// Length of the result: up to 2N, or to max_l when the caller asked for more
// (all_orders means "up to 2N").
inline std::size_t output_length(std::size_t terms, std::size_t max_l) {
  return (max_l == all_orders ? 2 * terms : max_l) + 1;
}

// Number of nodes needed for exact coefficients up to l = max_l with N terms.
inline std::size_t exact_order(std::size_t terms, std::size_t max_l) { return terms + (max_l + 2) / 2; }

// χ_l = ½ ∫ p P_l dμ for l = 0..max_l (entries above 2N are exactly zero),
// chunk by chunk of nodes (moments_chunk).  PerIsa as for moments_chunk_any (false:
// the kernel as compiled in the caller, which the tests compare bit for bit).
template <class Real, bool PerIsa = true>
std::vector<Real> legendre_moments(const std::vector<Complex<Real>>& a, const std::vector<Complex<Real>>& b,
                                   std::size_t max_l) {
  if (a.empty() || a.size() != b.size())
    throw std::invalid_argument(
        "Legendre moments need the Mie coefficients: call scatter() with extras.coefficients = true");
  const std::size_t nt = a.size(), lmax = std::min(max_l, 2 * nt);
  const HalfGaussLegendre<Real>& rule = cached_rule<Real>(exact_order(nt, lmax));
  const AmplitudeSeries<Real> c(a, b);
  const BonnetCoefficients<Real> k(lmax);
  const WeightedNodes<Real> nodes(rule, 1 / scattering_norm<Real>(a, b));
  std::vector<Real> acc((lmax + 1) * kLanes, Real(0));
  nodes.for_each_chunk([&](const Real* two_s, const Real* weight, std::size_t len, bool near) {
    moments_chunk_any<Real, PerIsa>(c, k, two_s, weight, len, near, lmax, acc.data());
  });
  std::vector<Real> chi(output_length(nt, max_l), Real(0));
  for (std::size_t l = 0; l <= lmax; ++l) chi[l] = lane_total(acc.data() + l * kLanes);
  return chi;
}

}  // namespace attenuvis::mie::detail

#include "attenuvis/mie/detail/gsf_coefficients_impl.hpp"
