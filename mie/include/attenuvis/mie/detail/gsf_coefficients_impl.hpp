// Expansion coefficients of the whole scattering matrix in generalised spherical
// functions (Wigner d-functions), templated on the floating type; the quadrature
// and its exactness are described in legendre_moments_impl.hpp, which includes
// this file.
//
// With the normalised matrix elements a1 = a2 = p, a3 = a4, b1, b2 of a sphere
// (legendre_moments.hpp) and d^l_{mn}(θ) as in Mishchenko, Travis & Lacis (2002,
// "Scattering, Absorption, and Emission of Light by Small Particles", eqs.
// 4.75–4.80 and their subroutine MATR):
//   α1^l       = (2l+1)/2 ∫ a1        d^l_{00}  dμ      (d^l_{00} = P_l)
//   α2^l+α3^l  = (2l+1)/2 ∫ (a2 + a3) d^l_{22}  dμ
//   α2^l−α3^l  = (2l+1)/2 ∫ (a2 − a3) d^l_{2,−2} dμ
//   α4^l       = (2l+1)/2 ∫ a4        d^l_{00}  dμ
//   β1^l, β2^l = (2l+1)/2 ∫ b1, b2    d^l_{02}  dμ
// from the orthogonality ∫ d^l_{mn} d^{l'}_{mn} dμ = 2/(2l+1) δ_{ll'}.
// Recurrences in l (MTL 2002 eq. B.22; the same as MATR), started at l = 2 with
//   d²_{22} = ((1+μ)/2)² = (1−s)²,  d²_{2,−2} = ((1−μ)/2)² = s²,
//   d²_{02} = (√6/4)(μ² − 1) = −√6 s(1−s),     d¹ = 0,
// s = (1−μ)/2 held exactly by the rule:
//   d^{l+1}_{2,±2} = [(2l+1)(l(l+1)μ ∓ 4) d^l − (l+1)(l²−4) d^{l−1}] / [l((l+1)²−4)]
//   d^{l+1}_{02}   = [(2l+1) μ d^l − √(l²−4) d^{l−1}] / √((l+1)²−4).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace attenuvis::mie::detail {

// The per-degree constants of the recurrences above, for l = 2..lmax (index l).
template <class Real>
struct WignerCoefficients {
  std::vector<Real> ll1, two_l1, slope, c_den, c_prev, z_den, z_prev;
  explicit WignerCoefficients(std::size_t lmax) {
    using std::sqrt;
    for (auto* v : {&ll1, &two_l1, &slope, &c_den, &c_prev, &z_den, &z_prev}) v->assign(lmax + 1, Real(0));
    for (std::size_t l = 2; l <= lmax; ++l) {
      const Real L = Real(l);
      ll1[l] = L * (L + 1);
      two_l1[l] = Real(2 * l + 1);
      slope[l] = two_l1[l] * ll1[l];
      c_den[l] = 1 / (L * ((L + 1) * (L + 1) - 4));
      c_prev[l] = (L + 1) * (L * L - 4);
      z_den[l] = 1 / sqrt((L + 1) * (L + 1) - 4);
      z_prev[l] = sqrt(L * L - 4);
    }
  }
};

// The six sums per degree that the coefficients are made of, each held as
// kLanes running sums (legendre_moments_impl.hpp: accumulate_chunk).
inline constexpr std::size_t kGsfSums = 6;  // a1·P, a4·P, (a2+a3)·d22, (a2−a3)·d2−2, b1·d02, b2·d02

// The normalised matrix elements at the ±μ of kChunk nodes (from the even and
// odd parts of S1, S2 that `amplitudes` gives), as the sweep over l needs them:
// P_l and d^l_{02} have parity (−1)^l, so they take the even/odd combinations
// f(μ) ± f(−μ); d^l_{22}(−μ) = (−1)^l d^l_{2,−2}(μ), so a2 ± a3 are kept per side.
template <class Real>
struct GsfProducts {
  Real a1e[kChunk], a1o[kChunk], a4e[kChunk], a4o[kChunk], b1e[kChunk], b1o[kChunk], b2e[kChunk], b2o[kChunk];
  Real sum0[kChunk], sum1[kChunk], diff0[kChunk], diff1[kChunk];  // a2 + a3, a2 − a3 at +μ [0] and −μ [1]

  // parts: S1 even r, i, odd r, i, then S2's; weight[j] = w_j / W; nodes >= len weigh nothing.
  ATTENUVIS_MIE_KERNEL void fill(const Real* const parts[8], const Real* weight, std::size_t len) {
    for (std::size_t j = 0; j < kChunk; ++j) {
      Real a1[2] = {0, 0}, a3[2] = {0, 0}, sm[2] = {0, 0}, df[2] = {0, 0}, b1[2] = {0, 0}, b2[2] = {0, 0};
      if (j < len) {
        const Real ww = weight[j];
        for (int side = 0; side < 2; ++side) {
          const Real s1r = side == 0 ? parts[0][j] + parts[2][j] : parts[0][j] - parts[2][j];
          const Real s1i = side == 0 ? parts[1][j] + parts[3][j] : parts[1][j] - parts[3][j];
          const Real s2r = side == 0 ? parts[4][j] + parts[6][j] : parts[4][j] - parts[6][j];
          const Real s2i = side == 0 ? parts[5][j] + parts[7][j] : parts[5][j] - parts[7][j];
          const Real i1 = s1r * s1r + s1i * s1i, i2 = s2r * s2r + s2i * s2i;
          const Real re = s2r * s1r + s2i * s1i, im = s2i * s1r - s2r * s1i;
          a1[side] = ww * (i1 + i2);                                                // a1 = p
          a3[side] = ww * 2 * re;                                                   // a3 = a4
          sm[side] = ww * ((s1r + s2r) * (s1r + s2r) + (s1i + s2i) * (s1i + s2i));  // a2 + a3
          df[side] = ww * ((s1r - s2r) * (s1r - s2r) + (s1i - s2i) * (s1i - s2i));  // a2 − a3
          b1[side] = ww * (i2 - i1);
          b2[side] = ww * (-2 * im);
        }
      }
      a1e[j] = a1[0] + a1[1], a1o[j] = a1[0] - a1[1];
      a4e[j] = a3[0] + a3[1], a4o[j] = a3[0] - a3[1];
      b1e[j] = b1[0] + b1[1], b1o[j] = b1[0] - b1[1];
      b2e[j] = b2[0] + b2[1], b2o[j] = b2[0] - b2[1];
      sum0[j] = sm[0], sum1[j] = sm[1], diff0[j] = df[0], diff1[j] = df[1];
    }
  }
};

// d^l_{22}, d^l_{2,−2}, d^l_{02} at kChunk nodes 2s = ts[j], from l = 2 up.
template <class Real>
struct WignerChunk {
  Real d22[kChunk], d22_prev[kChunk], e22[kChunk], d2m2[kChunk], d2m2_prev[kChunk], d02[kChunk], d02_prev[kChunk];

  explicit WignerChunk(const Real* ts) {
    using std::sqrt;
    const Real root6 = sqrt(Real(6));
    for (std::size_t j = 0; j < kChunk; ++j) {
      const Real s = ts[j] / 2;
      d22[j] = (1 - s) * (1 - s);  // ((1+μ)/2)²; d¹ = 0
      e22[j] = d22[j];
      d2m2[j] = s * s;                // ((1−μ)/2)²
      d02[j] = -root6 * s * (1 - s);  // (√6/4)(μ² − 1)
      d22_prev[j] = d2m2_prev[j] = d02_prev[j] = Real(0);
    }
  }

  // From degree l (>= 2) to l + 1 (recurrences in the header comment).
  template <bool NearForward>
  ATTENUVIS_MIE_KERNEL void advance(const WignerCoefficients<Real>& kw, std::size_t l, const Real* ts) {
    const Real ll1 = kw.ll1[l], two_l1 = kw.two_l1[l], slope = kw.slope[l];
    const Real c_den = kw.c_den[l], c_prev = kw.c_prev[l], z_den = kw.z_den[l], z_prev = kw.z_prev[l];
    for (std::size_t j = 0; j < kChunk; ++j) {
      const Real dp = d22[j], dm = d2m2[j], dz = d02[j], t = ts[j] * ll1;
      if constexpr (NearForward) {
        // d_{22} near μ = 1, where it is ~1 and carries the forward peak: on the
        // differences e = d^l − d^{l−1}, subtracting the μ = 1 identity
        // l((l+1)²−4) = (2l+1)(l(l+1)−4) − (l+1)(l²−4):
        //   e^{l+1} = [(l+1)(l²−4) e^l − 2s (2l+1) l(l+1) d^l] / [l((l+1)²−4)].
        e22[j] = (c_prev * e22[j] - ts[j] * slope * dp) * c_den;
        d22[j] = dp + e22[j];
      } else {
        // l(l+1)μ − 4 = (l(l+1) − 4) − 2s·l(l+1)
        d22[j] = (two_l1 * ((ll1 - 4) * dp - t * dp) - c_prev * d22_prev[j]) * c_den;
      }
      d22_prev[j] = dp;
      d2m2[j] = (two_l1 * ((ll1 + 4) * dm - t * dm) - c_prev * d2m2_prev[j]) * c_den;
      d2m2_prev[j] = dm;
      d02[j] = (two_l1 * (dz - ts[j] * dz) - z_prev * d02_prev[j]) * z_den;
      d02_prev[j] = dz;
    }
  }
};

// Adds to acc[(l·kGsfSums + k)·kLanes + lane] the share of `len` <= kChunk nodes,
// all on one side of s = ¼ (NearForward: s <= ¼), weight[j] = w_j / W:
// ∫ (a2+a3) d_{22} dμ = Σ w [f(+μ) d22(μ) + (−1)^l f(−μ) d2−2(μ)], likewise a2−a3;
// P_l runs as in moments_chunk.
template <class Real, bool NearForward>
ATTENUVIS_MIE_KERNEL void gsf_chunk(const AmplitudeSeries<Real>& c, const BonnetCoefficients<Real>& kp,
                                    const WignerCoefficients<Real>& kw, const Real* two_s, const Real* weight,
                                    std::size_t len, std::size_t lmax, Real* acc) {
  Real e1r[kChunk], e1i[kChunk], o1r[kChunk], o1i[kChunk], e2r[kChunk], e2i[kChunk], o2r[kChunk], o2i[kChunk];
  Real* const parts[8] = {e1r, e1i, o1r, o1i, e2r, e2i, o2r, o2i};
  amplitudes(c, two_s, len, NearForward, parts);
  GsfProducts<Real> f;
  f.fill(parts, weight, len);
  Real ts[kChunk], p0[kChunk], p1[kChunk], dp[kChunk];
  for (std::size_t j = 0; j < kChunk; ++j) {
    ts[j] = j < len ? two_s[j] : Real(0);
    p0[j] = 1;
    p1[j] = 1 - ts[j];
    dp[j] = -ts[j];
  }
  WignerChunk<Real> d(ts);
  Real prod_p[kChunk], prod_m[kChunk];
  for (std::size_t l = 0; l <= lmax; ++l) {
    const bool even = l % 2 == 0;
    Real* const at = acc + l * kGsfSums * kLanes;
    accumulate_chunk(even ? f.a1e : f.a1o, p0, at);
    accumulate_chunk(even ? f.a4e : f.a4o, p0, at + kLanes);
    bonnet_step<Real, NearForward>(kp.k1[l], kp.k2[l], ts, p0, p1, dp);
    if (l < 2) continue;
    const Real sign = even ? Real(1) : Real(-1);
    for (std::size_t j = 0; j < kChunk; ++j) {
      prod_p[j] = f.sum0[j] * d.d22[j] + sign * f.sum1[j] * d.d2m2[j];
      prod_m[j] = f.diff0[j] * d.d2m2[j] + sign * f.diff1[j] * d.d22[j];
    }
    accumulate_chunk_sum(prod_p, at + 2 * kLanes);
    accumulate_chunk_sum(prod_m, at + 3 * kLanes);
    accumulate_chunk(even ? f.b1e : f.b1o, d.d02, at + 4 * kLanes);
    accumulate_chunk(even ? f.b2e : f.b2o, d.d02, at + 5 * kLanes);
    d.template advance<NearForward>(kw, l, ts);
  }
}

// The double instance, compiled once per instruction set (mie/src/legendre_moments_double.cpp).
void gsf_chunk_double(const AmplitudeSeries<double>& c, const BonnetCoefficients<double>& kp,
                      const WignerCoefficients<double>& kw, const double* two_s, const double* weight,
                      std::size_t len, bool near, std::size_t lmax, double* acc);

template <class Real, bool PerIsa = true>
ScatteringMatrixExpansion<Real> gsf_coefficients(const std::vector<Complex<Real>>& a,
                                                 const std::vector<Complex<Real>>& b, std::size_t max_l) {
  if (a.empty() || a.size() != b.size())
    throw std::invalid_argument(
        "scattering-matrix expansion needs the Mie coefficients: call scatter() with "
        "extras.coefficients = true");
  const std::size_t nt = a.size(), lmax = std::min(max_l, 2 * nt);
  const HalfGaussLegendre<Real>& rule = cached_rule<Real>(exact_order(nt, lmax));
  const AmplitudeSeries<Real> c(a, b);
  const BonnetCoefficients<Real> kp(lmax);
  const WignerCoefficients<Real> kw(lmax);
  const WeightedNodes<Real> nodes(rule, 1 / scattering_norm<Real>(a, b));
  std::vector<Real> acc((lmax + 1) * kGsfSums * kLanes, Real(0));
  nodes.for_each_chunk([&](const Real* two_s, const Real* weight, std::size_t len, bool near) {
    if constexpr (PerIsa && std::is_same_v<Real, double>)
      gsf_chunk_double(c, kp, kw, two_s, weight, len, near, lmax, acc.data());
    else if (near)
      gsf_chunk<Real, true>(c, kp, kw, two_s, weight, len, lmax, acc.data());
    else
      gsf_chunk<Real, false>(c, kp, kw, two_s, weight, len, lmax, acc.data());
  });
  ScatteringMatrixExpansion<Real> out;
  for (auto* v : {&out.alpha1, &out.alpha2, &out.alpha3, &out.alpha4, &out.beta1, &out.beta2})
    v->assign(output_length(nt, max_l), Real(0));
  for (std::size_t l = 0; l <= lmax; ++l) {
    const Real* at = acc.data() + l * kGsfSums * kLanes;
    const Real half_norm = Real(2 * l + 1) / 2;
    out.alpha1[l] = half_norm * lane_total(at);
    out.alpha4[l] = half_norm * lane_total(at + kLanes);
    if (l < 2) continue;
    const Real plus = half_norm * lane_total(at + 2 * kLanes), minus = half_norm * lane_total(at + 3 * kLanes);
    out.alpha2[l] = (plus + minus) / 2;
    out.alpha3[l] = (plus - minus) / 2;
    out.beta1[l] = half_norm * lane_total(at + 4 * kLanes);
    out.beta2[l] = half_norm * lane_total(at + 5 * kLanes);
  }
  return out;
}

}  // namespace attenuvis::mie::detail
