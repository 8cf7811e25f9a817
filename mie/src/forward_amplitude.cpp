// S(0) at complex size parameter: see attenuvis/mie/forward_amplitude.hpp.
#include "attenuvis/mie/forward_amplitude.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "attenuvis/mie/detail/complex_ops.hpp"
#include "attenuvis/mie/detail/lentz.hpp"

namespace attenuvis::mie {
namespace {

void check(std::complex<double> x, std::complex<double> m) {
  const bool ok = std::isfinite(x.real()) && std::isfinite(x.imag()) && std::isfinite(m.real()) &&
                  std::isfinite(m.imag()) && x.real() > 0 && x.imag() >= 0 && x.imag() <= 20 &&
                  std::abs(x) <= 1e5 && m.real() > 0 && m.imag() >= 0 && std::abs(m - 1.0) >= 1e-6;
  if (!ok) {
    std::ostringstream os;
    os.precision(17);
    os << "mie::forward_amplitude: needs 0 < |x| <= 1e5, Re x > 0, 0 <= Im x <= 20, Re m > 0, Im m >= 0 and "
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

// S(0) at L size parameters at once, in arithmetic R.
template <class R, int L>
void evaluate(const std::complex<double>* x_in, std::complex<double> m_in, ForwardAmplitude* out) {
  using C = std::complex<R>;
  using V = Lanes<R, L>;
  const C m(m_in.real(), m_in.imag()), inv_m = detail::recip(m), i(0, 1);
  const R m_re = m.real(), m_im = m.imag(), im_re = inv_m.real(), im_im = inv_m.imag();
  const R eps = std::numeric_limits<R>::epsilon();
  R ax[L];
  V inv_x, inv_mx;
  // Terms beyond n ≈ |x| + 4|x|^{1/3} fall off faster than geometrically; the
  // sums stop when two successive terms no longer change them (below).  N is
  // only the length of the tables, shared by the lanes (Lentz's start is exact
  // at any order) and doubled if it was too short.
  std::size_t N = 0;
  for (int j = 0; j < L; ++j) {
    const C x(x_in[j].real(), x_in[j].imag());
    ax[j] = std::abs(x);
    N = std::max(N, static_cast<std::size_t>(ax[j] + 8 * std::cbrt(ax[j]) + 24));
    const C a = detail::recip(x), b = detail::recip(m * x);
    inv_x.re[j] = a.real(), inv_x.im[j] = a.imag(), inv_mx.re[j] = b.real(), inv_mx.im[j] = b.imag();
  }
  // Per order n: Dₙ(x), ψₙ/ψ_{n−1} at x, Dₙ(mx).
  thread_local std::vector<V> d_x, psi_up, d_mx;
  for (;;) {
    d_x.resize(N + 1);
    psi_up.resize(N + 1);
    d_mx.resize(N + 1);
    // Dₙ(z) by the downward recurrence D_{n−1} = n/z − 1/(Dₙ + n/z) (B&H
    // eq. 4.89), started from Lentz's continued fraction for ψ_{N−1}/ψ_N =
    // D_N + N/z.  The reciprocal 1/(Dₙ(x) + n/x) = ψₙ/ψ_{n−1} is kept: the
    // upward loop needs it.
    for (int j = 0; j < L; ++j) {
      const C ix(inv_x.re[j], inv_x.im[j]), imx(inv_mx.re[j], inv_mx.im[j]);
      const C a = detail::riccati_psi_ratio<C, R>(N, [&](R k) { return k * ix; }) - R(N) * ix;
      const C b = detail::riccati_psi_ratio<C, R>(N, [&](R k) { return k * imx; }) - R(N) * imx;
      d_x[N].re[j] = a.real(), d_x[N].im[j] = a.imag(), d_mx[N].re[j] = b.real(), d_mx[N].im[j] = b.imag();
    }
    for (std::size_t n = N; n >= 1; --n) {
      const R rn = R(n);
      const V &dx = d_x[n], &dmx = d_mx[n];
      V &up = psi_up[n], &dx_down = d_x[n - 1], &dmx_down = d_mx[n - 1];
      for (int j = 0; j < L; ++j) {
        const R ar = dx.re[j] + rn * inv_x.re[j], ai = dx.im[j] + rn * inv_x.im[j];
        const R br = dmx.re[j] + rn * inv_mx.re[j], bi = dmx.im[j] + rn * inv_mx.im[j];
        const R sa = 1 / (ar * ar + ai * ai), sb = 1 / (br * br + bi * bi);
        up.re[j] = ar * sa, up.im[j] = -ai * sa;
        dx_down.re[j] = rn * inv_x.re[j] - ar * sa, dx_down.im[j] = rn * inv_x.im[j] + ai * sa;
        dmx_down.re[j] = rn * inv_mx.re[j] - br * sb, dmx_down.im[j] = rn * inv_mx.im[j] + bi * sb;
      }
    }
    // ψ₀/ξ₀ = sin x / (−i e^{ix}) = i sin x e^{−ix}; ξ₀/ξ₁ = 1/(1/x − i); and
    // ξ_{n−1}/ξₙ = 1/((2n−1)/x − ξ_{n−2}/ξ_{n−1}) upward (stable for the
    // outgoing Hankel function).
    V t, xi_down, sum{};
    R magnitude[L] = {};
    int quiet[L] = {};
    bool done[L] = {};
    for (int j = 0; j < L; ++j) {
      const C x(x_in[j].real(), x_in[j].imag());
      const C t0 = i * std::sin(x) * std::exp(-i * x), q = detail::recip(C(inv_x.re[j], inv_x.im[j]) - i);
      t.re[j] = t0.real(), t.im[j] = t0.imag(), xi_down.re[j] = q.real(), xi_down.im[j] = q.imag();
    }
    int left = L;
    for (std::size_t n = 1; n <= N; ++n) {
      const R rn = R(n), weight = R(2 * n + 1);
      const V &dx = d_x[n], &dmx = d_mx[n], &up = psi_up[n];
      R term2[L], sum2[L];
      for (int j = 0; j < L; ++j) {
        const R qr = xi_down.re[j], qi = xi_down.im[j];  // ξ_{n−1}/ξₙ
        // ψₙ/ξₙ = (ψ_{n−1}/ξ_{n−1}) (ψₙ/ψ_{n−1}) (ξ_{n−1}/ξₙ)
        const R fr = up.re[j] * qr - up.im[j] * qi, fi = up.re[j] * qi + up.im[j] * qr;
        const R tr = t.re[j] * fr - t.im[j] * fi, ti = t.re[j] * fi + t.im[j] * fr;
        t.re[j] = tr, t.im[j] = ti;
        // aₙ = (ψₙ/ξₙ)(Dₙ(mx)/m − Dₙ(x)) / U,  U = Dₙ(mx)/m + n/x − ξ_{n−1}/ξₙ,
        // bₙ = (ψₙ/ξₙ)(m Dₙ(mx) − Dₙ(x)) / V,  V = m Dₙ(mx) + n/x − ξ_{n−1}/ξₙ
        // (B&H eq. 4.88 divided through by ξₙ); aₙ + bₙ over the one division 1/(UV).
        const R dr = dmx.re[j], di = dmx.im[j];
        const R pr = dr * im_re - di * im_im, pi = dr * im_im + di * im_re;  // Dₙ(mx)/m
        const R sr = m_re * dr - m_im * di, si = m_re * di + m_im * dr;      // m Dₙ(mx)
        const R nxr = rn * inv_x.re[j] - qr, nxi = rn * inv_x.im[j] - qi;
        const R Ur = pr + nxr, Ui = pi + nxi, Vr = sr + nxr, Vi = si + nxi;
        const R unr = pr - dx.re[j], uni = pi - dx.im[j], vnr = sr - dx.re[j], vni = si - dx.im[j];
        const R aVr = unr * Vr - uni * Vi, aVi = unr * Vi + uni * Vr;  // (Dₙ(mx)/m − Dₙ(x)) V
        const R bUr = vnr * Ur - vni * Ui, bUi = vnr * Ui + vni * Ur;  // (m Dₙ(mx) − Dₙ(x)) U
        const R UVr = Ur * Vr - Ui * Vi, UVi = Ur * Vi + Ui * Vr, s = 1 / (UVr * UVr + UVi * UVi);
        const R ir = UVr * s, ii = -UVi * s;
        const R nr = aVr + bUr, ni = aVi + bUi;
        const R gr = nr * ir - ni * ii, gi = nr * ii + ni * ir;
        const R er = weight * (tr * gr - ti * gi), ei = weight * (tr * gi + ti * gr);
        sum.re[j] += er, sum.im[j] += ei;
        // |aₙ| + |bₙ| <= |t| |1/(UV)| (|aV| + |bU|), each |z| <= |Re z| + |Im z|.
        magnitude[j] += weight * (std::abs(tr) + std::abs(ti)) * (std::abs(ir) + std::abs(ii)) *
                           (std::abs(aVr) + std::abs(aVi) + std::abs(bUr) + std::abs(bUi));
        term2[j] = er * er + ei * ei;
        sum2[j] = sum.re[j] * sum.re[j] + sum.im[j] * sum.im[j];
        // ξₙ/ξ_{n+1} = 1/((2(n+1)−1)/x − ξ_{n−1}/ξₙ) for the next order.
        const R ur = weight * inv_x.re[j] - qr, ui = weight * inv_x.im[j] - qi, s2 = 1 / (ur * ur + ui * ui);
        xi_down.re[j] = ur * s2, xi_down.im[j] = -ui * s2;
      }
      // A lane has converged once past |x| and two terms in a row are below
      // the last bit; it is read out then (the others go on).
      for (int j = 0; j < L; ++j) {
        if (done[j]) continue;
        if (rn > ax[j] && term2[j] <= eps * eps * sum2[j]) {
          if (++quiet[j] == 2) {
            done[j] = true;
            --left;
            out[j].s0 = std::complex<double>(double(sum.re[j] / 2), double(sum.im[j] / 2));
            out[j].magnitude = double(magnitude[j] / 2);
            out[j].terms = n;
            out[j].unit_roundoff = double(eps);
          }
        } else {
          quiet[j] = 0;
        }
      }
      if (left == 0) return;
    }
    N *= 2;  // a series had not converged within the tables: longer tables
  }
}

constexpr int kBatch = 4;

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
  for (std::size_t k = 0; k < count; k += kBatch) {
    // A short last batch repeats its last point.
    std::complex<double> xs[kBatch];
    ForwardAmplitude res[kBatch];
    for (int j = 0; j < kBatch; ++j) xs[j] = x[std::min(k + j, count - 1)];
    if (precision == Precision::extended) evaluate<long double, kBatch>(xs, m, res);
    else evaluate<double, kBatch>(xs, m, res);
    for (int j = 0; j < kBatch && k + j < count; ++j) out[k + j] = res[j];
  }
}

}  // namespace attenuvis::mie
