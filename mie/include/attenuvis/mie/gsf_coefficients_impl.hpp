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

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace attenuvis::mie::detail {

namespace gsf {

// Four partial sums, so that a node loop's additions need not be sequential.
template <class Real>
struct Lanes {
  std::array<Real, 4> v{Real(0), Real(0), Real(0), Real(0)};
  Real total() const { return (v[0] + v[1]) + (v[2] + v[3]); }
};

}  // namespace gsf

// d^l_{22}, d^l_{2,−2}, d^l_{02} at every node of a half rule, from l = 2 up, one
// degree at a time (recurrences in the header comment; d_{22} in difference form
// for s <= ¼).
template <class Real>
struct WignerSweep {
  // d^l (on entry to advance(l)) and d^{l−1} of each family; e22 = d^l_{22} − d^{l−1}_{22}.
  std::vector<Real> d22, d22_prev, e22, d2m2, d2m2_prev, d02, d02_prev, two_s;
  std::size_t split = 0;  // nodes [0, split) have s <= ¼

  explicit WignerSweep(const HalfGaussLegendre<Real>& rule) {
    using std::sqrt;
    const std::size_t m = rule.s.size();
    for (auto* v : {&d22, &d22_prev, &e22, &d2m2, &d2m2_prev, &d02, &d02_prev, &two_s}) v->assign(m, Real(0));
    for (std::size_t j = 0; j < m; ++j) {
      const Real s = rule.s[j];
      two_s[j] = 2 * s;
      if (s <= Real(0.25)) split = j + 1;
      d22[j] = (1 - s) * (1 - s);  // ((1+μ)/2)²; d¹ = 0
      e22[j] = d22[j];
      d2m2[j] = s * s;  // ((1−μ)/2)²
      d02[j] = -sqrt(Real(6)) * s * (1 - s);  // (√6/4)(μ² − 1)
    }
  }

  // From degree l (>= 2) to l + 1.
  void advance(std::size_t l) {
    using std::sqrt;
    const Real L = Real(l), ll1 = L * (L + 1), two_l1 = Real(2 * l + 1), slope = two_l1 * ll1;
    const Real c_den = 1 / (L * ((L + 1) * (L + 1) - 4)), c_prev = (L + 1) * (L * L - 4);
    const Real z_den = 1 / sqrt((L + 1) * (L + 1) - 4), z_prev = sqrt(L * L - 4);
    for (std::size_t j = 0; j < d22.size(); ++j) {
      const Real dp = d22[j], dm = d2m2[j], dz = d02[j], t = two_s[j] * ll1;
      if (j < split) {
        // d_{22} near μ = 1, where it is ~1 and carries the forward peak: on the
        // differences e = d^l − d^{l−1}, subtracting the μ = 1 identity
        // l((l+1)²−4) = (2l+1)(l(l+1)−4) − (l+1)(l²−4):
        //   e^{l+1} = [(l+1)(l²−4) e^l − 2s (2l+1) l(l+1) d^l] / [l((l+1)²−4)].
        e22[j] = (c_prev * e22[j] - two_s[j] * slope * dp) * c_den;
        d22[j] = dp + e22[j];
      } else {
        // l(l+1)μ − 4 = (l(l+1) − 4) − 2s·l(l+1)
        d22[j] = (two_l1 * ((ll1 - 4) * dp - t * dp) - c_prev * d22_prev[j]) * c_den;
      }
      d22_prev[j] = dp;
      d2m2[j] = (two_l1 * ((ll1 + 4) * dm - t * dm) - c_prev * d2m2_prev[j]) * c_den;
      d2m2_prev[j] = dm;
      d02[j] = (two_l1 * (dz - two_s[j] * dz) - z_prev * d02_prev[j]) * z_den;
      d02_prev[j] = dz;
    }
  }
};

template <class Real>
ScatteringMatrixExpansion<Real> gsf_coefficients(const std::vector<Complex<Real>>& a,
                                             const std::vector<Complex<Real>>& b, std::size_t max_l) {
  if (a.empty() || a.size() != b.size())
    throw std::invalid_argument(
        "scattering-matrix expansion needs the Mie coefficients: call scatter() with "
        "extras.coefficients = true");
  const std::size_t nt = a.size(), lmax = std::min(max_l, 2 * nt);
  const HalfGaussLegendre<Real>& rule = cached_rule<Real>(exact_order(nt, lmax));
  const WeightedProducts<Real> f = weighted_products<Real>(a, b, rule, true);
  const std::size_t m = rule.s.size();

  // Even/odd combinations for the parity-(−1)^l functions P_l and d^l_{02}.
  std::vector<Real> a1e(m), a1o(m), a4e(m), a4o(m), b1e(m), b1o(m), b2e(m), b2o(m);
  for (std::size_t j = 0; j < m; ++j) {
    a1e[j] = f.a1[0][j] + f.a1[1][j];
    a1o[j] = f.a1[0][j] - f.a1[1][j];
    a4e[j] = f.a3[0][j] + f.a3[1][j];
    a4o[j] = f.a3[0][j] - f.a3[1][j];
    b1e[j] = f.b1[0][j] + f.b1[1][j];
    b1o[j] = f.b1[0][j] - f.b1[1][j];
    b2e[j] = f.b2[0][j] + f.b2[1][j];
    b2o[j] = f.b2[0][j] - f.b2[1][j];
  }
  ScatteringMatrixExpansion<Real> out;
  for (auto* v : {&out.alpha1, &out.alpha2, &out.alpha3, &out.alpha4, &out.beta1, &out.beta2})
    v->assign(output_length(nt, max_l), Real(0));
  LegendreSweep<Real> p(rule);
  WignerSweep<Real> d(rule);
  for (std::size_t l = 0; l <= lmax; ++l) {
    const bool even = l % 2 == 0;
    const Real half_norm = Real(2 * l + 1) / 2;
    out.alpha1[l] = half_norm * dot4(even ? a1e : a1o, p.p0);
    out.alpha4[l] = half_norm * dot4(even ? a4e : a4o, p.p0);
    p.advance(l);
    if (l < 2) continue;
    // ∫ (a2+a3) d_{22} dμ = Σ w [f(+μ) d22(μ) + f(−μ) (−1)^l d2−2(μ)]; likewise a2−a3.
    const Real sign = even ? Real(1) : Real(-1);
    gsf::Lanes<Real> sp, sm;
    for (std::size_t j = 0; j < m; ++j) {
      sp.v[j % 4] += f.sum[0][j] * d.d22[j] + sign * f.sum[1][j] * d.d2m2[j];
      sm.v[j % 4] += f.diff[0][j] * d.d2m2[j] + sign * f.diff[1][j] * d.d22[j];
    }
    const Real plus = half_norm * sp.total(), minus = half_norm * sm.total();
    out.alpha2[l] = (plus + minus) / 2;
    out.alpha3[l] = (plus - minus) / 2;
    out.beta1[l] = half_norm * dot4(even ? b1e : b1o, d.d02);
    out.beta2[l] = half_norm * dot4(even ? b2e : b2o, d.d02);
    d.advance(l);
  }
  return out;
}

}  // namespace attenuvis::mie::detail
