// S(0) at complex size parameter: see attenuvis/mie/forward_amplitude.hpp.
#include "attenuvis/mie/forward_amplitude.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/mie/detail/complex_ops.hpp"
#include "instruction_set_clones.hpp"

namespace attenuvis::mie {
namespace {

void check(std::complex<double> x, std::complex<double> m) {
  const bool ok = std::isfinite(x.real()) && std::isfinite(x.imag()) && std::isfinite(m.real()) &&
                  std::isfinite(m.imag()) && x.real() > 0 && x.imag() >= 0 && x.imag() <= 20 &&
                  std::abs(x) <= kForwardAmplitudeMaxX && m.real() > 0 && m.imag() >= 0 && std::abs(m - 1.0) >= 1e-6;
  if (!ok) {
    std::ostringstream os;
    os.precision(17);
    static_assert(kForwardAmplitudeMaxX == 3e5, "the message names the limit as 3e5");
    os << "mie::forward_amplitude: needs 0 < |x| <= 3e5, Re x > 0, 0 <= Im x <= 20, Re m > 0, Im m >= 0 and "
          "|m - 1| >= 1e-6; got x = "
       << x.real() << (x.imag() < 0 ? " - " : " + ") << std::abs(x.imag()) << "i, m = " << m.real()
       << (m.imag() < 0 ? " - " : " + ") << std::abs(m.imag()) << "i";
    throw std::invalid_argument(os.str());
  }
}

// L complex numbers as separate real and imaginary arrays, so that the loops
// over lanes below are plain arithmetic the compiler can vectorise (several
// independent recurrences in flight also hide the division latency that
// bounds a single one).
template <class R, int L>
struct Lanes {
  R re[L], im[L];
};

// The per-call constants of L series: m, 1/m, |x|, 1/x and 1/(mx) per lane,
// and the length of the tables.
template <class R, int L>
struct ForwardProblem {
  std::complex<R> m, inv_m;
  R ax[L];
  Lanes<R, L> inv_x, inv_mx;
  // Terms beyond n ≈ |x| + 4|x|^{1/3} fall off faster than geometrically; the
  // sums stop when two successive terms no longer change them
  // (sum_forward_series).  N is only the length of the tables, shared by the
  // lanes (Lentz's start is exact at any order) and doubled if it was too short.
  std::size_t N = 0;
  ForwardProblem(const std::complex<double>* x_in, std::complex<double> m_in)
      : m(m_in.real(), m_in.imag()), inv_m(detail::recip(m)) {
    using C = std::complex<R>;
    R largest = 0;
    for (int j = 0; j < L; ++j) {
      const C x(x_in[j].real(), x_in[j].imag());
      ax[j] = std::abs(x);
      largest = std::max(largest, ax[j]);
      const C a = detail::recip(x), b = detail::recip(m * x);
      inv_x.re[j] = a.real(), inv_x.im[j] = a.imag(), inv_mx.re[j] = b.real(), inv_mx.im[j] = b.imag();
    }
    N = table_length(largest);
  }
  // Tables for series up to |z|: the largest lane's (one cube root per batch).
  static std::size_t table_length(R largest_abs_z) {
    return static_cast<std::size_t>(largest_abs_z + 8 * std::cbrt(largest_abs_z) + 24);
  }
};

// Per order n <= N: ψₙ/ψ_{n−1} at x and Dₙ(mx).  Dₙ(x) is not kept: it is
// (n+1)/x − ψ_{n+1}/ψₙ (B&H eq. 4.89), the same operation, in the same
// order, that produced it, so the sums read it back bit for bit from one
// table fewer (the tables are much of the series' memory traffic).
template <class R, int L>
struct ForwardTables {
  std::vector<Lanes<R, L>> psi_up, d_mx;
};

// ψ_{N−1}/ψ_N at the L arguments z = 1/inv_z: Lentz's continued fraction
// of detail/lentz.hpp (riccati_psi_ratio, with the same operations in the
// same order, written out on separate real and imaginary lanes) run on all
// lanes at once, each lane frozen once its own test passes.  The fraction
// takes about |z| − N steps for N below |z| (two divisions each), a few dozen
// past it: downward_log_derivatives starts Dₙ(mx) past |mx| for that reason.
template <class R, int L>
Lanes<R, L> psi_ratio_lanes(std::size_t N, const Lanes<R, L>& inv_z) {
  const R eps = std::numeric_limits<R>::epsilon();
  const R eps2 = eps * eps;
  const R tiny = (std::numeric_limits<R>::min)() * R(1e20);
  Lanes<R, L> f, c, d{};
  const R b0 = detail::index_real<R>(2 * N + 1);
  for (int j = 0; j < L; ++j) {
    f.re[j] = b0 * inv_z.re[j], f.im[j] = b0 * inv_z.im[j];
    if (f.re[j] == 0 && f.im[j] == 0) f.re[j] = tiny, f.im[j] = 0;
    c.re[j] = f.re[j], c.im[j] = f.im[j];
  }
  // The zero tests and the freezing of finished lanes are selects, not
  // branches, so that the lane loop vectorises; each lane performs the
  // operations of the scalar fraction in the same order.
  R frozen[L] = {};  // 1 once a lane has converged
  int left = L;
  const std::size_t max_iterations = 400000000;
  for (std::size_t k = 1; k <= max_iterations && left > 0; ++k) {
    const R bk = detail::index_real<R>(2 * N + 1 + 2 * k);
    R passed[L];
    for (int j = 0; j < L; ++j) {
      const R br = bk * inv_z.re[j], bi = bk * inv_z.im[j];
      R dr = br - d.re[j], di = bi - d.im[j];
      const bool d_zero = dr == 0 && di == 0;
      dr = d_zero ? tiny : dr, di = d_zero ? R(0) : di;
      const R sc = 1 / (c.re[j] * c.re[j] + c.im[j] * c.im[j]);
      R cr = br - c.re[j] * sc, ci = bi - (-c.im[j] * sc);
      const bool c_zero = cr == 0 && ci == 0;
      cr = c_zero ? tiny : cr, ci = c_zero ? R(0) : ci;
      const R sd = 1 / (dr * dr + di * di);
      dr = dr * sd, di = -di * sd;
      const R er = cr * dr - ci * di, ei = cr * di + ci * dr;  // delta = c d
      const R fr = f.re[j] * er - f.im[j] * ei, fi = f.re[j] * ei + f.im[j] * er;
      const R gr = er - 1, gi = ei - 0;
      passed[j] = gr * gr + gi * gi < eps2 ? R(1) : R(0);
      const bool keep = frozen[j] != 0;
      d.re[j] = keep ? d.re[j] : dr, d.im[j] = keep ? d.im[j] : di;
      c.re[j] = keep ? c.re[j] : cr, c.im[j] = keep ? c.im[j] : ci;
      f.re[j] = keep ? f.re[j] : fr, f.im[j] = keep ? f.im[j] : fi;
    }
    for (int j = 0; j < L; ++j)
      if (frozen[j] == 0 && passed[j] != 0) frozen[j] = 1, --left;
  }
  if (left > 0)
    throw std::runtime_error("attenuvis::mie: Lentz continued fraction did not converge for n=" + std::to_string(N));
  return f;
}

// Dₙ(z) by the downward recurrence D_{n−1} = n/z − 1/(Dₙ + n/z) (B&H eq. 4.89),
// started from Lentz's continued fraction for ψ_{N−1}/ψ_N = D_N + N/z.  The
// reciprocal 1/(Dₙ(x) + n/x) = ψₙ/ψ_{n−1} is kept: the upward loop needs it.
template <class R, int L>
void downward_log_derivatives(const ForwardProblem<R, L>& p, std::size_t N, ForwardTables<R, L>& t) {
  using V = Lanes<R, L>;
  const V &inv_x = p.inv_x, &inv_mx = p.inv_mx;
  t.psi_up.resize(N + 2);
  t.d_mx.resize(N + 1);
  // Dₙ(mx) starts at N_mx >= N past |mx| (m > 1 puts |mx| beyond the tables),
  // where the continued fraction takes a few dozen steps instead of the
  // ~|mx| − N it needs at N, and runs down to N by the recurrence: one
  // division per order instead of the fraction's two.
  R largest_mx = 0;
  for (int j = 0; j < L; ++j) largest_mx = std::max(largest_mx, 1 / std::hypot(inv_mx.re[j], inv_mx.im[j]));
  const std::size_t N_mx = std::max(N, ForwardProblem<R, L>::table_length(largest_mx));
  const V start_x = psi_ratio_lanes(N, inv_x), start_mx = psi_ratio_lanes(N_mx, inv_mx);
  V dx, d_mx;
  for (int j = 0; j < L; ++j) {
    dx.re[j] = start_x.re[j] - R(N) * inv_x.re[j], dx.im[j] = start_x.im[j] - R(N) * inv_x.im[j];
    // A ψ_{N+1}/ψ_N that gives back D_N(x) through (N+1)/x − ψ_{N+1}/ψ_N
    // to within a rounding (the series has converged long before order N).
    t.psi_up[N + 1].re[j] = R(N + 1) * inv_x.re[j] - dx.re[j];
    t.psi_up[N + 1].im[j] = R(N + 1) * inv_x.im[j] - dx.im[j];
    d_mx.re[j] = start_mx.re[j] - R(N_mx) * inv_mx.re[j], d_mx.im[j] = start_mx.im[j] - R(N_mx) * inv_mx.im[j];
  }
  for (std::size_t n = N_mx; n > N; --n) {
    const R rn = detail::index_real<R>(n);
    // Not unrolled: GCC unrolls this short lane loop in full and then leaves
    // it scalar (sixteen scalar divisions per order, ~9 % of an evaluation
    // at |x| = 400); as a loop it is vectorised.
#pragma GCC unroll 1
    for (int j = 0; j < L; ++j) {
      const R br = d_mx.re[j] + rn * inv_mx.re[j], bi = d_mx.im[j] + rn * inv_mx.im[j];
      const R sb = 1 / (br * br + bi * bi);
      d_mx.re[j] = rn * inv_mx.re[j] - br * sb, d_mx.im[j] = rn * inv_mx.im[j] + bi * sb;
    }
  }
  // The running Dₙ are carried in locals, not read back from the tables: the
  // recurrence is a chain of dependent divisions, and a store-to-load round
  // trip per order would lengthen it.
  t.d_mx[N] = d_mx;
  for (std::size_t n = N; n >= 1; --n) {
    const R rn = R(n);
    V up;
    for (int j = 0; j < L; ++j) {
      const R ar = dx.re[j] + rn * inv_x.re[j], ai = dx.im[j] + rn * inv_x.im[j];
      const R br = d_mx.re[j] + rn * inv_mx.re[j], bi = d_mx.im[j] + rn * inv_mx.im[j];
      const R sa = 1 / (ar * ar + ai * ai), sb = 1 / (br * br + bi * bi);
      up.re[j] = ar * sa, up.im[j] = -ai * sa;
      dx.re[j] = rn * inv_x.re[j] - ar * sa, dx.im[j] = rn * inv_x.im[j] + ai * sa;
      d_mx.re[j] = rn * inv_mx.re[j] - br * sb, d_mx.im[j] = rn * inv_mx.im[j] + bi * sb;
    }
    t.psi_up[n] = up, t.d_mx[n - 1] = d_mx;
  }
}

// The running state of the L upward series: ψₙ/ξₙ, ξₙ/ξₙ₊₁ (for the next
// order), the sums, and the convergence count per lane.
template <class R, int L>
struct ForwardSums {
  Lanes<R, L> t, xi_down, sum{};
  R magnitude[L] = {};
  int quiet[L] = {};
  bool done[L] = {};
  int left = L;
};

// Order n of every lane: ψₙ/ξₙ = (ψ_{n−1}/ξ_{n−1}) (ψₙ/ψ_{n−1}) (ξ_{n−1}/ξₙ),
// then aₙ + bₙ added to the sums; term2, sum2: |term|², |sum|² for the
// convergence test (only computed when `test`: none is made below the
// smallest |x|).
template <bool test, class R, int L>
void add_forward_order(const ForwardProblem<R, L>& p, const ForwardTables<R, L>& tables, std::size_t n,
                       ForwardSums<R, L>& s, R* term2, R* sum2) {
  const R m_re = p.m.real(), m_im = p.m.imag(), im_re = p.inv_m.real(), im_im = p.inv_m.imag();
  const R rn = R(n), weight = R(2 * n + 1), rn1 = R(n + 1);
  const Lanes<R, L> &dmx = tables.d_mx[n], &up = tables.psi_up[n], &up1 = tables.psi_up[n + 1], &inv_x = p.inv_x;
  for (int j = 0; j < L; ++j) {
    const R dxr = rn1 * inv_x.re[j] - up1.re[j], dxi = rn1 * inv_x.im[j] - up1.im[j];  // Dₙ(x)
    const R qr = s.xi_down.re[j], qi = s.xi_down.im[j];  // ξ_{n−1}/ξₙ
    const R fr = up.re[j] * qr - up.im[j] * qi, fi = up.re[j] * qi + up.im[j] * qr;
    const R tr = s.t.re[j] * fr - s.t.im[j] * fi, ti = s.t.re[j] * fi + s.t.im[j] * fr;
    s.t.re[j] = tr, s.t.im[j] = ti;
    // aₙ = (ψₙ/ξₙ)(Dₙ(mx)/m − Dₙ(x)) / U,  U = Dₙ(mx)/m + n/x − ξ_{n−1}/ξₙ,
    // bₙ = (ψₙ/ξₙ)(m Dₙ(mx) − Dₙ(x)) / V,  V = m Dₙ(mx) + n/x − ξ_{n−1}/ξₙ
    // (B&H eq. 4.88 divided through by ξₙ); aₙ + bₙ over the one division 1/(UV).
    const R dr = dmx.re[j], di = dmx.im[j];
    const R pr = dr * im_re - di * im_im, pi = dr * im_im + di * im_re;  // Dₙ(mx)/m
    const R sr = m_re * dr - m_im * di, si = m_re * di + m_im * dr;      // m Dₙ(mx)
    const R nxr = rn * inv_x.re[j] - qr, nxi = rn * inv_x.im[j] - qi;
    const R Ur = pr + nxr, Ui = pi + nxi, Vr = sr + nxr, Vi = si + nxi;
    const R unr = pr - dxr, uni = pi - dxi, vnr = sr - dxr, vni = si - dxi;
    const R aVr = unr * Vr - uni * Vi, aVi = unr * Vi + uni * Vr;  // (Dₙ(mx)/m − Dₙ(x)) V
    const R bUr = vnr * Ur - vni * Ui, bUi = vnr * Ui + vni * Ur;  // (m Dₙ(mx) − Dₙ(x)) U
    const R UVr = Ur * Vr - Ui * Vi, UVi = Ur * Vi + Ui * Vr, q = 1 / (UVr * UVr + UVi * UVi);
    const R ir = UVr * q, ii = -UVi * q;
    const R nr = aVr + bUr, ni = aVi + bUi;
    const R gr = nr * ir - ni * ii, gi = nr * ii + ni * ir;
    const R er = weight * (tr * gr - ti * gi), ei = weight * (tr * gi + ti * gr);
    s.sum.re[j] += er, s.sum.im[j] += ei;
    // |aₙ| + |bₙ| <= |t| |1/(UV)| (|aV| + |bU|), each |z| <= |Re z| + |Im z|.
    s.magnitude[j] += weight * (std::abs(tr) + std::abs(ti)) * (std::abs(ir) + std::abs(ii)) *
                      (std::abs(aVr) + std::abs(aVi) + std::abs(bUr) + std::abs(bUi));
    if constexpr (test) {
      term2[j] = er * er + ei * ei;
      sum2[j] = s.sum.re[j] * s.sum.re[j] + s.sum.im[j] * s.sum.im[j];
    }
    // ξₙ/ξ_{n+1} = 1/((2(n+1)−1)/x − ξ_{n−1}/ξₙ) for the next order.
    const R ur = weight * inv_x.re[j] - qr, ui = weight * inv_x.im[j] - qi, s2 = 1 / (ur * ur + ui * ui);
    s.xi_down.re[j] = ur * s2, s.xi_down.im[j] = -ui * s2;
  }
}

// The series upward over the tables.  A lane has converged once past |x| and
// two terms in a row are below the last bit; it is read out then (the others
// go on).  Returns false if some lane had not converged by order N.
template <class R, int L>
bool sum_forward_series(const std::complex<double>* x_in, const ForwardProblem<R, L>& p,
                        const ForwardTables<R, L>& tables, std::size_t N, ForwardAmplitude* out) {
  using C = std::complex<R>;
  const R eps = std::numeric_limits<R>::epsilon();
  const C i(0, 1);
  // ψ₀/ξ₀ = sin x / (−i e^{ix}) = i sin x e^{−ix}; ξ₀/ξ₁ = 1/(1/x − i); and
  // ξ_{n−1}/ξₙ = 1/((2n−1)/x − ξ_{n−2}/ξ_{n−1}) upward (stable for the
  // outgoing Hankel function).
  ForwardSums<R, L> s;
  for (int j = 0; j < L; ++j) {
    const C x(x_in[j].real(), x_in[j].imag());
    const C t0 = i * std::sin(x) * std::exp(-i * x), q = detail::recip(C(p.inv_x.re[j], p.inv_x.im[j]) - i);
    s.t.re[j] = t0.real(), s.t.im[j] = t0.imag(), s.xi_down.re[j] = q.real(), s.xi_down.im[j] = q.imag();
  }
  // No lane can stop at orders up to the smallest |x|: the tests start above it.
  const R first_test = *std::min_element(p.ax, p.ax + L);
  std::size_t n = 1;
  R* const untested = nullptr;
  for (; n <= N && !(R(n) > first_test); ++n) add_forward_order<false>(p, tables, n, s, untested, untested);
  for (; n <= N; ++n) {
    const R rn = R(n);
    R term2[L], sum2[L];
    add_forward_order<true>(p, tables, n, s, term2, sum2);
    for (int j = 0; j < L; ++j) {
      if (s.done[j]) continue;
      if (rn > p.ax[j] && term2[j] <= eps * eps * sum2[j]) {
        if (++s.quiet[j] == 2) {
          s.done[j] = true;
          --s.left;
          out[j].s0 = std::complex<double>(double(s.sum.re[j] / 2), double(s.sum.im[j] / 2));
          out[j].magnitude = double(s.magnitude[j] / 2);
          out[j].terms = n;
          out[j].unit_roundoff = double(eps);
        }
      } else {
        s.quiet[j] = 0;
      }
    }
    if (s.left == 0) return true;
  }
  return false;
}

// S(0) at L size parameters at once, in arithmetic R.
template <class R, int L>
void evaluate(const std::complex<double>* x_in, std::complex<double> m_in, ForwardAmplitude* out) {
  const ForwardProblem<R, L> problem(x_in, m_in);
  thread_local ForwardTables<R, L> tables;
  // A series that has not converged within the tables runs again on longer ones.
  for (std::size_t N = problem.N;; N *= 2) {
    downward_log_derivatives(problem, N, tables);
    if (sum_forward_series(x_in, problem, tables, N, out)) return;
  }
}

// Series per batch.  Sixteen side by side hide more of the latency of each
// recurrence's divisions than eight, at every |x| now that the tables are
// two (2 x 16 bytes per series and order, kept per thread: 10 MB at
// |x| = 2e4, 51 MB at 1e5): 143 against 122-130 us per point at |x| = 3e4,
// 240 against 203-215 at 5e4 (validation/bench/forward_amplitude_speed).
// With three tables sixteen gained nothing above |x| ~ 2e4 and took eight.
constexpr int kBatch = 8, kWideBatch = 16;

// The double series of one batch, compiled once per instruction set (the
// series are inlined into each clone, flatten): the lane loops above then run
// on the vectors of AVX2 or AVX-512 instead of the baseline's two lanes.  The
// library is built without contraction, so every clone returns the same bits.
ATTENUVIS_MIE_CLONES __attribute__((flatten)) void evaluate_batch_double(const std::complex<double>* x,
                                                                         std::complex<double> m,
                                                                         ForwardAmplitude* out) {
  evaluate<double, kBatch>(x, m, out);
}
ATTENUVIS_MIE_CLONES __attribute__((flatten)) void evaluate_wide_batch_double(const std::complex<double>* x,
                                                                              std::complex<double> m,
                                                                              ForwardAmplitude* out) {
  evaluate<double, kWideBatch>(x, m, out);
}

// x[k, k + L) in one batch of L (a short last batch repeats its last point).
template <int L, class Evaluate>
void run_batch(const std::complex<double>* x, std::size_t k, std::size_t count, std::complex<double> m,
               Evaluate&& evaluate_batch, ForwardAmplitude* out) {
  std::complex<double> xs[L];
  ForwardAmplitude res[L];
  for (int j = 0; j < L; ++j) xs[j] = x[std::min(k + j, count - 1)];
  evaluate_batch(xs, m, res);
  for (int j = 0; j < L && k + j < count; ++j) out[k + j] = res[j];
}

}  // namespace

double ForwardAmplitude::rounding_bound() const {
  return static_cast<double>(terms) * unit_roundoff * magnitude +
         2 * std::numeric_limits<double>::epsilon() * std::abs(s0);
}

ForwardAmplitude forward_amplitude(std::complex<double> x, std::complex<double> m, Precision precision) {
  check(x, m);
  ForwardAmplitude out;
  if (precision == Precision::extended) evaluate<long double, 1>(&x, m, &out);
  else evaluate<double, 1>(&x, m, &out);
  return out;
}

void forward_amplitudes(const std::complex<double>* x, std::size_t count, std::complex<double> m,
                        Precision precision, ForwardAmplitude* out) {
  for (std::size_t k = 0; k < count; ++k) check(x[k], m);
  if (precision == Precision::extended) {  // scalar arithmetic: no gain from wider batches
    for (std::size_t k = 0; k < count; k += kBatch)
      run_batch<kBatch>(x, k, count, m, evaluate<long double, kBatch>, out);
    return;
  }
  for (std::size_t k = 0; k < count;) {
    const std::size_t end = std::min(k + kWideBatch, count);
    // Eight points or fewer (a 7-point panel) fill a batch of eight.
    const bool wide = end - k > kBatch;
    if (wide) run_batch<kWideBatch>(x, k, count, m, evaluate_wide_batch_double, out);
    else run_batch<kBatch>(x, k, count, m, evaluate_batch_double, out);
    k += wide ? kWideBatch : kBatch;
  }
}

}  // namespace attenuvis::mie
