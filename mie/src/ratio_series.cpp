// The ratios of the downward pass from power series: see
// attenuvis/mie/ratio_series.hpp for the expansion and its domain.
#include "attenuvis/mie/ratio_series.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "instruction_set_clones.hpp"

namespace attenuvis::mie::detail {
namespace {

constexpr std::size_t kOrders = 40;  // orders n = 0 .. 39 (a multiple of the 8 lanes below)
constexpr std::size_t kTerms = 40;   // powers u^0 .. u^39
constexpr double kMaxX = 1.5, kMaxAbsMx = 1.6;  // cos x > 0 below π/2 (see the ρₙ loop)
constexpr double kPi2 = 9.8696044010893586188;  // π², j½,₁ = π

// φₙₖ, row k holding every order n (one vector load per block of orders).
//
// From the downward recurrence yₙ = 1/((2n+3)/z − yₙ₊₁) with yₙ = z fₙ(z²):
//     fₙ(u) = 1/((2n+3) − u fₙ₊₁(u)),
// so φₙ₀ = 1/(2n+3) and φₙₖ = Σⱼ₌₁..ₖ φₙ₊₁,ⱼ₋₁ φₙ,ₖ₋ⱼ /(2n+3): sums of
// products of positive numbers, no cancellation (checked against
// y₀(x) = 1/x − cot x = x/3 + x³/45 + 2x⁵/945 + … in the tests).  φₙₖ
// depends on φₙ₊ⱼ,ₖ₋ⱼ only, so rows started at n = kOrders + kTerms from
// their exact constant term alone are exact (up to rounding) for n < kOrders,
// k < kTerms.  Long double: each coefficient within a few ulps of double.
//
// sₙₖ: ψₙ(x) = x^{n+1}/(2n+1)!! Sₙ(x²), Sₙ(u) = Σₖ sₙₖ uᵏ with sₙ₀ = 1,
// sₙₖ = −sₙ,ₖ₋₁/(2k (2n+2k+1)) (DLMF 10.53.1).  Sₙ is entire; its tail after
// K >= 4 terms is below (u/6)ᴷ/K! <= (u/π²)ᴷ, and |Sₙ| >= 2 − e^{u/6} > 0.54
// for u <= 2.25, so the K of the ratios (TermThresholds) serves it too.
struct Coefficients {
  alignas(64) double phi[kTerms][kOrders];
  alignas(64) double sphi[kTerms][kOrders];
  Coefficients() {
    constexpr std::size_t top = kOrders + kTerms;
    std::vector<std::array<long double, kTerms>> f(top + 2);
    for (std::size_t n = top + 1;; --n) {
      const long double inv = 1.0L / static_cast<long double>(2 * n + 3);
      f[n][0] = inv;
      for (std::size_t k = 1; k < kTerms; ++k) {
        long double s = 0;
        if (n <= top)
          for (std::size_t j = 1; j <= k; ++j) s += f[n + 1][j - 1] * f[n][k - j];
        f[n][k] = s * inv;
      }
      if (n == 0) break;
    }
    for (std::size_t k = 0; k < kTerms; ++k)
      for (std::size_t n = 0; n < kOrders; ++n) phi[k][n] = static_cast<double>(f[n][k]);
    for (std::size_t n = 0; n < kOrders; ++n) {
      long double v = 1;
      for (std::size_t k = 0; k < kTerms; ++k) {
        sphi[k][n] = static_cast<double>(v);
        v *= -1.0L / static_cast<long double>(2 * (k + 1) * (2 * n + 2 * k + 3));
      }
    }
  }
};

const Coefficients& coefficients() {
  static const Coefficients c;
  return c;
}

// The number of terms K for a block of orders whose smallest first zero is
// j (q = R/j², R = max(|u|, |u_m|)).  Truncation after K terms leaves, by the
// header's bounds (φₙₖ <= φₙ₁ j^{−2(k−1)}, |h_{k−1}(u_m, u)| <= k R^{k−1}),
// at most φₙ₁ K q^{K−1}/(1 − q)² in the divided difference and less in fₙ;
// both are bounded below by (1 − q)/(1 + q)² times φₙ₁ and φₙ₀ (every
// partial fraction 2/(j²ₛ − u) has a positive real part that large).  So
//     K q^{K−1} (1 + q)²/(1 − q)³ <= ε/16
// keeps the truncation of every yₙ, δₙ below ε/16 relative.  The largest q
// each K allows is tabulated once (bisection), so a call only compares.
struct TermThresholds {
  double q_max[kTerms + 1] = {};
  static double bound(std::size_t K, double q) {
    return static_cast<double>(K) * std::pow(q, static_cast<double>(K) - 1) * (1 + q) * (1 + q) /
           ((1 - q) * (1 - q) * (1 - q));
  }
  TermThresholds() {
    const double tol = std::numeric_limits<double>::epsilon() / 16;
    for (std::size_t K = 2; K <= kTerms; ++K) {
      double lo = 0, hi = 0.99;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (bound(K, mid) <= tol ? lo : hi) = mid;
      }
      q_max[K] = lo;
    }
  }
};

const TermThresholds& thresholds() {
  static const TermThresholds t;
  return t;
}

// 0 when q needs more terms than the table holds.
std::size_t terms_for(double q) {
  const TermThresholds& t = thresholds();
  for (std::size_t K = 2; K <= kTerms; ++K)
    if (q <= t.q_max[K]) return K;
  return 0;
}

// A lower bound of j²ₙ₊½,₁ for every order >= n: the Rayleigh sum
// σ₂(ν) = Σ j⁻⁴ₛ = 1/(16 (ν+1)² (ν+2)) >= j⁻⁴₁ gives j²₁ >= 4 (ν+1) √(ν+2)
// (DLMF §10.21(viii)), and j₁ grows with ν; for n = 0 the exact π² is larger.
double first_zero_squared_bound(std::size_t n) {
  const double nu = static_cast<double>(n) + 0.5;
  return std::max(kPi2, 4 * (nu + 1) * std::sqrt(nu + 2));
}

typedef double V8 __attribute__((vector_size(64)));

V8 load(const double* p) {
  V8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
void store_v(double* p, const V8& v) { std::memcpy(p, &v, sizeof v); }

// Horner over u (real) and u_m (complex) for eight orders at once, with the
// divided difference (synthetic division): for P(t) = Σₖ<K cₖ tᵏ,
// Bₖ = cₖ + u_m Bₖ₊₁, P(u_m) = B₀ and P[u_m, u] = Σⱼ₌₁..K−1 Bⱼ u^{j−1}.
// Eight lanes as one 64-byte vector: one register with AVX-512, split by the
// compiler otherwise (arithmetic only, no vector compares).
inline __attribute__((always_inline)) void horner_block(const Coefficients& c, std::size_t first, std::size_t K, double u, double umr, double umi,
                  double* fx, double* fmr, double* fmi, double* ddr, double* ddi, double* sx) {
  V8 f = {}, g = {}, br = {}, bi = {}, dr = {}, di = {};
  for (std::size_t k = K - 1; k >= 1; --k) {
    const V8 ck = load(&c.phi[k][first]);
    f = ck + u * f;
    g = load(&c.sphi[k][first]) + u * g;
    const V8 nbr = ck + (umr * br - umi * bi);
    const V8 nbi = umr * bi + umi * br;
    br = nbr, bi = nbi;
    dr = br + u * dr;
    di = bi + u * di;
  }
  const V8 c0 = load(&c.phi[0][first]);
  store_v(fx + first, c0 + u * f);
  store_v(fmr + first, c0 + (umr * br - umi * bi));
  store_v(fmi + first, umr * bi + umi * br);
  store_v(ddr + first, dr);
  store_v(ddi + first, di);
  store_v(sx + first, load(&c.sphi[0][first]) + u * g);
}

}  // namespace

bool in_series_domain(double x, std::complex<double> m) {
  const double zr = m.real() * x, zi = m.imag() * x;
  return x <= kMaxX && zr * zr + zi * zi <= kMaxAbsMx * kMaxAbsMx;
}

std::size_t series_ratio_terms(double r) { return terms_for(r); }

ATTENUVIS_MIE_CLONES
bool series_ratios(double x, std::complex<double> m, std::size_t N, Slot slot, double sin_x, double cos_x,
                   const SeriesTables& t) {
  if (N + 2 > kOrders) return false;
  const std::size_t count = N + 1;
  // ηₙ, n = 0 .. N+1 (see the ρₙ loop below): a chain independent of the
  // series, first, so that its latency overlaps the polynomials.
  // With them, the prefactors x^{n+1}/(2n+1)!! of ψₙ (a product chain too).
  alignas(64) double eta[kOrders + 1], lead[kOrders + 1];
  const double inv_x = 1 / x;
  double e0 = sin_x, e1 = -cos_x;  // ηₙ₋₂, ηₙ₋₁ in registers (the chain's latency is the cost)
  double l = x;
  eta[0] = e1;
  lead[0] = l;
  for (std::size_t n = 1; n <= count; ++n) {
    const double e = static_cast<double>(2 * n - 1) * inv_x * e1 - e0;
    eta[n] = e;
    e0 = e1, e1 = e;
    lead[n] = l = l * (x / static_cast<double>(2 * n + 1));
  }
  // |ξₙ|² must stay finite (it does for every table at x >= 1e-8 but the
  // longest ones at the smallest x).
  if (!(std::abs(eta[count]) < 1e150)) return false;

  const Coefficients& c = coefficients();
  const double u = x * x;
  const double zr = m.real() * x, zi = m.imag() * x;       // m x
  const double umr = zr * zr - zi * zi, umi = 2 * zr * zi;  // u_m = (m x)²
  const double R = std::max(u, std::sqrt(umr * umr + umi * umi));
  alignas(64) double fx[kOrders], fmr[kOrders], fmi[kOrders], ddr[kOrders], ddi[kOrders], sx[kOrders];
  for (std::size_t first = 0; first <= count; first += 8) {  // fₙ to N, Sₙ to N + 1
    const std::size_t K = terms_for(R / first_zero_squared_bound(first));
    if (K == 0) return false;
    horner_block(c, first, std::max<std::size_t>(K, 4), u, umr, umi, fx, fmr, fmi, ddr, ddi, sx);
  }
  // u_m − u = (m² − 1) x² and m − 1, each formed without cancellation
  // (m.real() − 1 is exact for 0.5 <= Re m <= 2, Sterbenz).
  const double m1r = m.real() - 1, m1i = m.imag();
  const double er = m1r * (m.real() + 1) - m1i * m1i, ei = m1r * m1i + m1i * (m.real() + 1);  // m² − 1
  const double dur = er * u, dui = ei * u;
  // yₙ(x), yₙ(mx) and δₙ order by order (SoA, so that the loop runs in
  // vector lanes), then stored into the interleaved tables.
  alignas(64) double yzr[kOrders], yzi[kOrders], dr[kOrders], di[kOrders];
  for (std::size_t n = 0; n < count; ++n) {
    fx[n] = x * fx[n];                                                       // yₙ(x)
    yzr[n] = zr * fmr[n] - zi * fmi[n], yzi[n] = zr * fmi[n] + zi * fmr[n];  // yₙ(m x)
    // δₙ = x [(m − 1) fₙ(u_m) + (u_m − u) fₙ[u_m, u]]
    dr[n] = x * ((m1r * fmr[n] - m1i * fmi[n]) + (dur * ddr[n] - dui * ddi[n]));
    di[n] = x * ((m1r * fmi[n] + m1i * fmr[n]) + (dur * ddi[n] + dui * ddr[n]));
  }
  if (slot == Slot::difference) {
    for (std::size_t n = 0; n < count; ++n) {
      const bool value = 64 * (yzr[n] * yzr[n] + yzi[n] * yzi[n]) < fx[n] * fx[n];  // the rule of downward_ratios
      t.y[n] = fx[n];
      t.is_value[n] = value;
      t.w[n].re = value ? yzr[n] : dr[n];
      t.w[n].im = value ? yzi[n] : di[n];
    }
  } else {
    for (std::size_t n = 0; n < count; ++n) t.y[n] = fx[n], t.w[n].re = yzr[n], t.w[n].im = yzi[n];
  }
  // ξₙ = ψₙ + i ηₙ with ψₙ from its series; η₋₁ = sin x, η₀ = −cos x,
  // ηₙ = (2n−1)/x ηₙ₋₁ − ηₙ₋₂ (upward: ηₙ is the dominant solution).  For
  // x < π/2 every ψₙ > 0 and every ηₙ < 0 (|η₁| = cos x/x + sin x > |η₀|,
  // and with (2n−1)/x >= 2 the recurrence keeps the sign and |ηₙ| >= |ηₙ₋₁|), so
  //   ρₙ = (ψₙ₋₁ψₙ + ηₙ₋₁ηₙ + i (ηₙ₋₁ψₙ − ψₙ₋₁ηₙ))/|ξₙ|²
  // has a real part of terms of one sign, and its imaginary part is the
  // Casoratian of the recurrence, exactly 1 for every n (ψₙ₋₁ηₙ − ψₙηₙ₋₁
  // does not change when the recurrence is substituted, and ψ₀η₁ − ψ₁η₀ =
  // −sin²x − cos²x): Im ρₙ = 1/|ξₙ|² is taken as such, not formed by
  // subtraction.  Rₙ = ψₙ/ξₙ = (ψₙ² − i ψₙηₙ)/|ξₙ|².
  alignas(64) double psi[kOrders + 1], rr[kOrders + 1], sr[kOrders + 1], Rr[kOrders + 1], Ri[kOrders + 1];
  for (std::size_t n = 0; n <= count; ++n) psi[n] = lead[n] * sx[n];
  for (std::size_t n = 1; n <= count; ++n) {
    const double a = psi[n - 1], b = eta[n - 1], pn = psi[n], e = eta[n];
    const double sn = 1 / (pn * pn + e * e);
    rr[n] = (a * pn + b * e) * sn;
    sr[n] = sn;
    Rr[n] = pn * pn * sn;
    Ri[n] = -(pn * e) * sn;
  }
  for (std::size_t n = 1; n <= count; ++n) t.rho[n].re = rr[n], t.rho[n].im = sr[n];
  for (std::size_t n = 1; n < count; ++n) t.R[n].re = Rr[n], t.R[n].im = Ri[n], t.s[n] = sr[n];
  return true;
}

}  // namespace attenuvis::mie::detail
