// Two alternative formulations of the Mie core's ratio recurrences, timed in
// isolation against the ones the core uses, with their errors.  Both were
// candidates for a faster core and both were measured slower or no faster:
// this benchmark is the evidence behind the README's "Benchmarks" section.
//
// 1. Large x: the downward recurrences yₙ(x), yₙ(mx), the difference δₙ and
//    the upward Hankel ratio ρₙ (log_derivative.hpp) over N ≈ x + 4 x^⅓
//    steps, in
//      long double   x87 80-bit, what the core runs above x = 1e4
//      double        not accurate enough there (its ρₙ error is shown)
//      compensated   double with a first-order error term per value, the
//                    local rounding errors formed exactly by error-free
//                    transformations (two-sum, FMA residuals): a
//                    double-double-class replacement for x87 (δₙ left
//                    plain, so its time is a lower bound)
//    ns per step, and the largest relative error of yₙ(x) and ρₙ against the
//    same recurrences in 113-bit binary floating point (Boost), all from the
//    same start (zeros at N).  yₙ(x) inherits the rounding of 1/x itself
//    (64 bits in long double and here, 113 in the reference), ρₙ does not.
// 2. Small x: the same ratios for n <= N by power series in x² and (mx)²,
//    every order independent (Horner across orders, vectorisable; δₙ by
//    divided differences, so nothing cancels at m near 1; ρₙ from the series
//    of ψₙ and χₙ), against the core's own downward pass (downward_ratios)
//    with its table length and Miller start.  ns per call and the largest relative
//    difference between the two.
//
// Usage: mie_formulations   (a few seconds; one thread)
#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "attenuvis/mie/detail/log_derivative.hpp"
#include "attenuvis/mie/detail/term_count.hpp"

namespace {

volatile double g_sink;

// Minimum over `blocks` of the time of f() in ns.
template <class F>
double min_ns(F&& f, int blocks) {
  double best = 1e300;
  for (int b = 0; b < blocks; ++b) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// ---- 1. Large x ------------------------------------------------------------

// The tables of one downward pass (index n) and Hankel ratio (index j).
template <class R>
struct RatioTables {
  std::vector<R> y, rho_re, rho_im, y_err, rho_re_err, rho_im_err;  // *_err: compensated only
  explicit RatioTables(long n)
      : y(n + 2), rho_re(n + 2), rho_im(n + 2), y_err(n + 2), rho_re_err(n + 2), rho_im_err(n + 2) {}
};

// The core's step (downward_ratios with HankelRatio, Slot::difference) in
// real type R, complex parts spelled out.
template <class R>
void plain_pass(double x, std::complex<double> m, long N, RatioTables<R>& t) {
  const R mr(m.real()), mi(m.imag()), xr(x);
  const R ix = R(1) / xr, zr = mr * xr, zi = mi * xr, zn = zr * zr + zi * zi;
  const R izr = zr / zn, izi = -zi / zn;
  const R cr = (mr - R(1)) * izr - mi * izi, ci = (mr - R(1)) * izi + mi * izr;  // (m−1)/(mx)
  R yx(0), yzr(0), yzi(0), dr(0), di(0), rr(0), ri(1);
  for (long n = N;; --n) {
    t.y[n] = yx;
    const long j = N + 1 - n;
    const R ur = R(2 * j - 1) * ix - rr, ui = -ri, su = R(1) / (ur * ur + ui * ui);
    rr = ur * su, ri = -ui * su;
    t.rho_re[j] = rr, t.rho_im[j] = ri;
    if (n == 0) break;
    const R k(2 * n + 1);
    const R sx = k * ix - yx, szr = k * izr - yzr, szi = k * izi - yzi;
    yx = R(1) / sx;
    const R s = R(1) / (szr * szr + szi * szi);
    yzr = szr * s, yzi = -szi * s;
    const R tr = cr * k + dr, ti = ci * k + di;
    dr = (tr * yzr - ti * yzi) * yx, di = (tr * yzi + ti * yzr) * yx;
  }
}

#if defined(__GNUC__) && defined(__x86_64__)
#define ATTENUVIS_FMA_TARGET __attribute__((target("fma")))
#define ATTENUVIS_HAVE_FMA_PROBE 1
#else
#define ATTENUVIS_FMA_TARGET
#endif

// a + b = s + e exactly (Knuth's two-sum).
ATTENUVIS_FMA_TARGET inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// r + re ≈ 1/((ah + al) − (y + ye)) for real values: r = fl(1/s) with s the
// rounded difference; re = r (1 − s r − r dl) to first order, where dl
// collects the difference's exact rounding error, al and −ye, and 1 − s r is
// exact by FMA.
ATTENUVIS_FMA_TARGET inline void compensated_recip(double ah, double al, double y, double ye, double& r, double& re) {
  double s, t;
  two_sum(ah, -y, s, t);
  const double dl = (t + al) - ye;
  r = 1.0 / s;
  re = r * (std::fma(-s, r, 1.0) - r * dl);
}

// The same for complex values (parts spelled out); 1 − s r is formed from
// the exact products (FMA) and two-sums, since its real part cancels to ~ε.
ATTENUVIS_FMA_TARGET inline void compensated_recip(const double ah[2], const double al[2], const double y[2],
                                                   const double ye[2], double r[2], double re[2]) {
  double sr, tr, si, ti;
  two_sum(ah[0], -y[0], sr, tr);
  two_sum(ah[1], -y[1], si, ti);
  const double dlr = (tr + al[0]) - ye[0], dli = (ti + al[1]) - ye[1];
  const double q = 1.0 / (sr * sr + si * si);
  r[0] = sr * q, r[1] = -si * q;
  const double p1 = sr * r[0], p1e = std::fma(sr, r[0], -p1), p2 = si * r[1], p2e = std::fma(si, r[1], -p2);
  double a, ae, b, be;
  two_sum(1.0, -p1, a, ae);
  two_sum(a, p2, b, be);
  const double res_r = b + ((ae + be) + (p2e - p1e));
  const double p3 = sr * r[1], p3e = std::fma(sr, r[1], -p3), p4 = si * r[0], p4e = std::fma(si, r[0], -p4);
  const double res_i = -((p3 + p4) + (p3e + p4e));
  const double ur = res_r - (r[0] * dlr - r[1] * dli), ui = res_i - (r[0] * dli + r[1] * dlr);
  re[0] = r[0] * ur - r[1] * ui, re[1] = r[0] * ui + r[1] * ur;
}

// k·(hi + lo) as a double pair (exact product by FMA, plus k·lo).
ATTENUVIS_FMA_TARGET inline void scaled(double k, double hi, double lo, double& h, double& l) {
  h = k * hi;
  l = std::fma(k, hi, -h) + k * lo;
}

// plain_pass with every ratio compensated (δ stays plain: it is damped).
ATTENUVIS_FMA_TARGET void compensated_pass(double x, std::complex<double> m, long N, RatioTables<double>& t) {
  // 1/x and 1/(mx) as the core rounds them (x87 quotient, split into a
  // double and its remainder): the same constants as the core's double path.
  namespace core = attenuvis::mie::detail;
  const core::ScaledInverse<double> over_x(x);
  const core::ScaledInverseComplex<double, std::complex<double>> over_mx(x, m);
  const double ixh = over_x.hi, ixlo = over_x.split.lo;
  const double izh[2] = {over_mx.hi.real(), over_mx.hi.imag()};
  const double izlo[2] = {over_mx.re.lo, over_mx.im.lo};
  const std::complex<double> c = (m - 1.0) * over_mx.hi;
  double yx = 0, yxe = 0, yz[2] = {0, 0}, yze[2] = {0, 0}, d[2] = {0, 0}, rho[2] = {0, 1}, rhoe[2] = {0, 0};
  for (long n = N;; --n) {
    t.y[n] = yx, t.y_err[n] = yxe;
    const long j = N + 1 - n;
    double ah[2] = {0, 0}, al[2] = {0, 0}, nr[2], ne[2];
    scaled(double(2 * j - 1), ixh, ixlo, ah[0], al[0]);
    compensated_recip(ah, al, rho, rhoe, nr, ne);
    rho[0] = nr[0], rho[1] = nr[1], rhoe[0] = ne[0], rhoe[1] = ne[1];
    t.rho_re[j] = rho[0], t.rho_im[j] = rho[1], t.rho_re_err[j] = rhoe[0], t.rho_im_err[j] = rhoe[1];
    if (n == 0) break;
    const double k = double(2 * n + 1);
    double h, l;
    scaled(k, ixh, ixlo, h, l);
    compensated_recip(h, l, yx, yxe, yx, yxe);
    scaled(k, izh[0], izlo[0], ah[0], al[0]);
    scaled(k, izh[1], izlo[1], ah[1], al[1]);
    compensated_recip(ah, al, yz, yze, nr, ne);
    yz[0] = nr[0], yz[1] = nr[1], yze[0] = ne[0], yze[1] = ne[1];
    const double tr = c.real() * k + d[0], ti = c.imag() * k + d[1];
    d[0] = (tr * yz[0] - ti * yz[1]) * yx, d[1] = (tr * yz[1] + ti * yz[0]) * yx;
  }
}

using Quad = boost::multiprecision::cpp_bin_float_quad;

// Largest relative error of y (n = 0..N) and ρ (j = 1..N+1) against q.
template <class R>
void errors(const RatioTables<R>& t, const RatioTables<Quad>& q, long N, bool compensated, double& ey, double& erho) {
  ey = erho = 0;
  for (long n = 0; n <= N; ++n) {
    if (q.y[n] == 0) continue;
    const Quad v = Quad(t.y[n]) + (compensated ? Quad(t.y_err[n]) : Quad(0));
    ey = std::max(ey, double(abs((v - q.y[n]) / q.y[n])));
  }
  for (long j = 1; j <= N + 1; ++j) {
    const Quad vr = Quad(t.rho_re[j]) + (compensated ? Quad(t.rho_re_err[j]) : Quad(0));
    const Quad vi = Quad(t.rho_im[j]) + (compensated ? Quad(t.rho_im_err[j]) : Quad(0));
    const Quad dr = vr - q.rho_re[j], di = vi - q.rho_im[j];
    erho = std::max(erho, double(sqrt((dr * dr + di * di) / (q.rho_re[j] * q.rho_re[j] + q.rho_im[j] * q.rho_im[j]))));
  }
}

void large_x(double x, std::complex<double> m) {
  const long N = long(attenuvis::mie::detail::first_terms<double>(x, attenuvis::mie::detail::bound_cbrt(x)));
  RatioTables<long double> tl(N);
  RatioTables<double> td(N), tc(N);
  RatioTables<Quad> tq(N);
  plain_pass(x, m, N, tq);
  const double ns_l = min_ns([&] { plain_pass(x, m, N, tl); }, 9) / double(N);
  const double ns_d = min_ns([&] { plain_pass(x, m, N, td); }, 9) / double(N);
  double ey, erho;
  std::printf("x = %g, m = %g%+gi, %ld steps (downward y(x), y(mx), delta; upward rho)\n", x, m.real(), m.imag(), N);
  std::printf("  %-12s %10s %16s %16s\n", "recurrences", "ns/step", "max err y_n(x)", "max err rho_n");
  errors(tl, tq, N, false, ey, erho);
  std::printf("  %-12s %10.2f %16.1e %16.1e\n", "long double", ns_l, ey, erho);
  errors(td, tq, N, false, ey, erho);
  std::printf("  %-12s %10.2f %16.1e %16.1e\n", "double", ns_d, ey, erho);
#ifdef ATTENUVIS_HAVE_FMA_PROBE
  if (!__builtin_cpu_supports("fma")) {
    std::printf("  compensated: this CPU has no FMA\n");
    return;
  }
  const double ns_c = min_ns([&] { compensated_pass(x, m, N, tc); }, 9) / double(N);
  errors(tc, tq, N, true, ey, erho);
  std::printf("  %-12s %10.2f %16.1e %16.1e\n", "compensated", ns_c, ey, erho);
#endif
}

// ---- 2. Small x -------------------------------------------------------------

constexpr int kMaxOrder = 24, kMaxTerms = 24;

// Coefficients of the normalised series, by term k then order n (so that a
// Horner step runs across orders):
//   ψₙ(z) = z^{n+1}/(2n+1)!! Pₙ(z²),  Pₙ(w) = Σ_k p[k][n] w^k,  p_k = p_{k−1} (−1/2)/(k (2n+2k+1))
//   χₙ(z) = (2n−1)!!/zⁿ Sₙ(z²),      Sₙ(w) = Σ_k s[k][n] w^k,  s_k = s_{k−1} (−1/2)/(k (2k−1−2n))
// (Abramowitz & Stegun 10.1.2–10.1.3, with χₙ = −z yₙ(z)).
struct SeriesCoefficients {
  alignas(64) double p[kMaxTerms + 1][kMaxOrder + 2];
  alignas(64) double s[kMaxTerms + 1][kMaxOrder + 2];
  SeriesCoefficients() {
    for (int n = 0; n <= kMaxOrder + 1; ++n) {
      p[0][n] = s[0][n] = 1;
      for (int k = 1; k <= kMaxTerms; ++k) {
        p[k][n] = p[k - 1][n] * -0.5 / (k * (2.0 * n + 2 * k + 1));
        s[k][n] = s[k - 1][n] * -0.5 / (k * (2.0 * k - 1 - 2 * n));
      }
    }
  }
};
const SeriesCoefficients kSeries;

// Terms K such that every neglected term of Pₙ, Sₙ (n <= N + 1) is below ε/16
// of the leading one at |w| <= w_max.
int series_terms(double w_max, int N) {
  for (int K = 1; K < kMaxTerms; ++K) {
    double worst = 0;
    for (int n = 0; n <= N + 1; ++n)
      worst = std::max({worst, std::abs(kSeries.p[K][n]), std::abs(kSeries.s[K][n])});
    if (worst * std::pow(w_max, K) < 0x1p-56) return K;
  }
  return kMaxTerms;
}

struct SmallTables {
  double y[kMaxOrder + 1], w_re[kMaxOrder + 1], w_im[kMaxOrder + 1], rho_re[kMaxOrder + 2], rho_im[kMaxOrder + 2];
};

// yₙ(z) = z/(2n+3) · P_{n+1}(z²)/Pₙ(z²); δₙ = yₙ(mx) − yₙ(x) with the
// numerator (m−1) P_{n+1}(v) Pₙ(u) + (v−u)[ΔP_{n+1} Pₙ(u) − P_{n+1}(u) ΔPₙ]
// (ΔP = (P(v) − P(u))/(v − u) from the Horner quotient, v − u = (m²−1)u);
// ρⱼ = ξ_{j−1}/ξⱼ with ξⱼ = ψⱼ − iχⱼ.  Compiled per instruction set, as
// the core's term loops are, so that the Horner steps run in vector lanes.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void series_ratios(double x, std::complex<double> m, int N, int K, SmallTables& o) {
  const double u = x * x, vr = (m.real() * m.real() - m.imag() * m.imag()) * u, vi = 2 * m.real() * m.imag() * u;
  const int L = N + 2;
  alignas(64) double Pu[kMaxOrder + 2], Su[kMaxOrder + 2], Pr[kMaxOrder + 2], Pi[kMaxOrder + 2];
  alignas(64) double Dr[kMaxOrder + 2], Di[kMaxOrder + 2];
  for (int n = 0; n < L; ++n) Pu[n] = Pr[n] = kSeries.p[K][n], Su[n] = kSeries.s[K][n], Pi[n] = Dr[n] = Di[n] = 0;
  for (int k = K - 1; k >= 0; --k) {
    const double* pk = kSeries.p[k];
    const double* sk = kSeries.s[k];
    for (int n = 0; n < L; ++n) {
      Pu[n] = Pu[n] * u + pk[n];
      Su[n] = Su[n] * u + sk[n];
      Dr[n] = Dr[n] * u + Pr[n], Di[n] = Di[n] * u + Pi[n];
      const double nr = (Pr[n] * vr - Pi[n] * vi) + pk[n], ni = Pr[n] * vi + Pi[n] * vr;
      Pr[n] = nr, Pi[n] = ni;
    }
  }
  const double m1r = m.real() - 1, m1i = m.imag(), er = vr - u, ei = vi;  // m − 1, (m² − 1) u
  for (int n = 0; n <= N; ++n) {
    const double f = x / (2 * n + 3);
    o.y[n] = f * Pu[n + 1] / Pu[n];
    const double br = Dr[n + 1] * Pu[n] - Pu[n + 1] * Dr[n], bi = Di[n + 1] * Pu[n] - Pu[n + 1] * Di[n];
    const double ar = (m1r * Pr[n + 1] - m1i * Pi[n + 1]) * Pu[n], ai = (m1r * Pi[n + 1] + m1i * Pr[n + 1]) * Pu[n];
    const double numr = ar + (er * br - ei * bi), numi = ai + (er * bi + ei * br);
    const double denr = Pr[n] * Pu[n], deni = Pi[n] * Pu[n];
    const double q = f / (denr * denr + deni * deni);
    o.w_re[n] = (numr * denr + numi * deni) * q, o.w_im[n] = (numi * denr - numr * deni) * q;
  }
  double psi_scale = x, chi_scale = 1;  // x^{j+1}/(2j+1)!!, (2j−1)!!/x^j
  double prev_r = psi_scale * Pu[0], prev_i = -chi_scale * Su[0];
  for (int j = 1; j <= N + 1; ++j) {
    psi_scale *= x / (2 * j + 1), chi_scale *= (2 * j - 1) / x;
    const double cr = psi_scale * Pu[j], ci = -chi_scale * Su[j], q = 1 / (cr * cr + ci * ci);
    o.rho_re[j] = (prev_r * cr + prev_i * ci) * q, o.rho_im[j] = (prev_i * cr - prev_r * ci) * q;
    prev_r = cr, prev_i = ci;
  }
}

void small_x(double x, std::complex<double> m) {
  namespace d = attenuvis::mie::detail;
  using C = attenuvis::mie::Complex<double>;
  const int N = int(d::first_terms<double>(x, d::bound_cbrt(x)));  // the core's table length
  const int K = int(d::miller_depth(x, m, std::size_t(N)));
  if (N > kMaxOrder || K == 0) return;
  const int terms = series_terms(std::max(x * x, std::norm(m) * x * x), N);
  // The core's own downward pass (log_derivative.hpp) with its tables; the
  // correctly rounded k/x, k/(mx) of the eight x values are built outside
  // the timing, as the call builds them for its series too.
  constexpr int kCalls = 200000, kXs = 8;
  std::vector<d::ScaledInverse<double>> over_x;
  std::vector<d::ScaledInverseComplex<double, C>> over_mx;
  for (int i = 0; i < kXs; ++i) {
    over_x.emplace_back(x * (1 + 1e-12 * i));
    over_mx.emplace_back(x * (1 + 1e-12 * i), C(m.real(), m.imag()));
  }
  d::DownwardTables<double> core;
  const auto core_pass = [&](int i) {
    d::downward_ratios<double, C>(over_x[i], over_mx[i], C(m.real(), m.imag()), std::size_t(N), d::Slot::difference,
                                  core.y, core.rho, core.w, core.is_value, std::size_t(K));
  };
  SmallTables a{};
  const double ns_series = min_ns([&] {
    for (int i = 0; i < kCalls; ++i) series_ratios(x * (1 + 1e-12 * (i % kXs)), m, N, terms, a), g_sink = a.w_re[1];
  }, 9) / kCalls;
  const double ns_core = min_ns([&] {
    for (int i = 0; i < kCalls; ++i) core_pass(i % kXs), g_sink = core.w[1].real();
  }, 9) / kCalls;
  series_ratios(x, m, N, terms, a);
  core_pass(0);
  double diff = 0;
  for (int n = 0; n <= N; ++n) {
    const double y = core.y[n];
    // w holds δₙ, or yₙ(mx) itself where is_value is set.
    const double dr = core.w[n].real() - (core.is_value[n] ? y : 0.0), di = core.w[n].imag();
    const auto rho = core.rho[n + 1];
    diff = std::max(diff, std::abs(a.y[n] - y) / std::abs(y));
    diff = std::max(diff, std::hypot(a.w_re[n] - dr, a.w_im[n] - di) / std::hypot(dr, di));
    diff = std::max(diff, std::hypot(a.rho_re[n + 1] - rho.real(), a.rho_im[n + 1] - rho.imag()) /
                              std::hypot(rho.real(), rho.imag()));
  }
  std::printf("x = %g, m = %g%+gi: orders 0..%d; y_n(x), delta_n, rho_n per call\n", x, m.real(), m.imag(), N);
  std::printf("  downward from N + %d (the core)   %8.1f ns\n", K, ns_core);
  std::printf("  power series, %2d terms           %8.1f ns   (max relative difference %.1e)\n", terms, ns_series,
              diff);
}

}  // namespace

int main() {
  std::printf("Alternative formulations of the ratio recurrences (one thread; minimum over 9 blocks)\n\n");
  large_x(1e5, {1.33, 1e-8});
  std::printf("\n");
  small_x(0.1, {1.33, 1e-8});
  small_x(1.0, {1.33, 1e-8});
  g_sink = 0;
  return 0;
}
