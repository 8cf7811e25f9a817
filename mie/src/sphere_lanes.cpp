// kLanes spheres at once, one per vector lane: see sphere_lanes.hpp.  The
// lane loops below are plain arithmetic on arrays of kLanes doubles, which
// the compiler turns into vector instructions (one clone per instruction set,
// chosen at run time); each lane's operations are those of series.hpp.
#include "sphere_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "attenuvis/mie/series.hpp"
#include "sphere_checks.hpp"

namespace attenuvis::mie::detail {
namespace {

constexpr int L = kLanes;
using C = std::complex<double>;

// kLanes doubles / 64-bit masks in one GCC vector (split into SSE2, AVX2 or
// AVX-512 registers by the clone that runs).  Arithmetic is element-wise
// IEEE, so each lane computes what the scalar code computes.
typedef double V __attribute__((vector_size(8 * kLanes)));

// Helpers are inlined into each instruction-set clone of run_lanes (a call to
// a shared copy would run its SSE2 code).
#define ATTENUVIS_LANE_INLINE inline __attribute__((always_inline))
typedef long long M __attribute__((vector_size(8 * kLanes)));

// |v| by clearing the sign bit, as std::abs does.
inline V vabs(V v) { return (V)((M)v & (M{} + 0x7fffffffffffffffLL)); }

inline V splat(double v) { return V{} + v; }

// k/x and k/(mx) per lane, as SplitInverse (log_derivative.hpp) computes them.
struct LaneInverse {
  V h1, h2, lo;
  V at(double k) const { return k * h1 + (k * h2 + k * lo); }
  V at(V k) const { return k * h1 + (k * h2 + k * lo); }
};

// Lentz's continued fraction for ψ_{n-1}(z)/ψₙ(z) per lane, n = order[j]
// (riccati_psi_ratio in lentz.hpp, the same operations): z = x (im == nullptr)
// or z = mx.  A lane that has converged keeps its value while the others go on.
struct LaneLentz {
  V fr, fi;
  ATTENUVIS_LANE_INLINE LaneLentz(const LaneInverse& re, const LaneInverse* im, V order) {
    const double eps = std::numeric_limits<double>::epsilon(), eps2 = eps * eps;
    const V tiny = V{} + (std::numeric_limits<double>::min)() * 1e20, zero{}, one = V{} + 1.0;
    const bool complex = im != nullptr;
    const V k0 = 2 * order + 1;
    fr = re.at(k0);
    fi = complex ? im->at(k0) : zero;
    M f_zero = (fr == zero) & (fi == zero);
    fr = f_zero ? tiny : fr;
    fi = f_zero ? zero : fi;
    V cr = fr, ci = fi, dr = zero, di = zero;
    M done = zero != zero;
    for (long j = 1; j <= 400000000; ++j) {
      const V k = k0 + 2.0 * double(j);
      const V br = re.at(k), bi = complex ? im->at(k) : zero;
      dr = br - dr, di = bi - di;
      const M d_zero = (dr == zero) & (di == zero);
      dr = d_zero ? tiny : dr, di = d_zero ? zero : di;
      // c = b − 1/c
      V icr, ici;
      if (complex) {
        const V sc = 1 / (cr * cr + ci * ci);
        icr = cr * sc, ici = -ci * sc;
      } else {
        icr = one / cr, ici = zero;
      }
      cr = br - icr, ci = bi - ici;
      const M c_zero = (cr == zero) & (ci == zero);
      cr = c_zero ? tiny : cr, ci = c_zero ? zero : ci;
      // d = 1/d
      if (complex) {
        const V sd = 1 / (dr * dr + di * di);
        dr = dr * sd, di = -di * sd;
      } else {
        dr = one / dr;
      }
      const V er = cr * dr - ci * di, ei = complex ? cr * di + ci * dr : zero;  // δ = c d
      const V nfr = complex ? fr * er - fi * ei : fr * er;
      const V nfi = complex ? fr * ei + fi * er : zero;
      fr = done ? fr : nfr, fi = done ? fi : nfi;
      const V e1 = er - 1.0, e2 = ei - 0.0;
      const V mag = complex ? e1 * e1 + e2 * e2 : e1 * e1;
      done |= mag < eps2;
      bool all = true;
      for (int l = 0; l < L; ++l) all &= done[l] != 0;
      if (all) return;
    }
    throw std::runtime_error("attenuvis::mie: Lentz continued fraction did not converge");
  }
};

// Compensated sum per lane (KahanSum in series.hpp), advanced where `on`.
struct LaneKahan {
  V sum{}, carry{};
  void add(V v, M on) {
    const V y = v - carry;
    const V t = sum + y;
    const V c = (t - sum) - y;
    sum = on ? t : sum;
    carry = on ? c : carry;
  }
  V value() const { return sum - carry; }
};

// Per-thread tables of the downward pass, one vector per order n, in plain
// double arrays (std::vector of an over-aligned vector type was not aligned
// by this standard library); loads and stores go through memcpy.
struct LaneTables {
  std::vector<double> y, w_re, w_im, use_d;
  void resize(std::size_t N) {
    const std::size_t n = (N + 1) * L;
    if (y.size() < n) y.resize(n), w_re.resize(n), w_im.resize(n), use_d.resize(n);
  }
};

template <class T>
inline T load(const double* p) {
  T v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
inline void save(double* p, const T& v) {
  __builtin_memcpy(p, &v, sizeof v);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define ATTENUVIS_MIE_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ATTENUVIS_MIE_CLONES
#endif

// Per-lane constants and start values (as mie_series/sum_series/downward_ratios).
struct LaneState {
  std::size_t N = 0;      // longest table of the lanes
  std::size_t start = 0;  // highest start index of the downward pass
  V x, Njd, start_d, mr, mi, m1r, m1i, cr, ci, er, ei, cdr, cdi, yx0, yzr0, yzi0, dr0, di0, Rr, Ri;
  M diff_slot;
  LaneInverse ox{}, ozr{}, ozi{};
};

ATTENUVIS_LANE_INLINE void lane_setup(const LaneProblems& in, LaneState& st) {
  std::size_t miller[L];
  bool any_lentz = false;
  for (int j = 0; j < L; ++j) {
    st.x[j] = in.x[j];
    const double x = in.x[j];
    const C m = in.m[j];
    const std::size_t Nj = first_terms<double>(x, std::cbrt(x));
    st.N = std::max(st.N, Nj);
    st.Njd[j] = double(Nj);
    // Start of the downward pass: Lentz at N, or zeros at N + K (miller_depth).
    miller[j] = miller_depth(x, m, Nj);
    st.start = std::max(st.start, Nj + miller[j]);
    st.start_d[j] = double(Nj + miller[j]);
    any_lentz |= miller[j] == 0;
    const C dm = m - 1.0;
    st.diff_slot[j] = norm2(dm) < 0.25 ? -1 : 0;
    const ScaledInverse<double> over_x(x);
    const ScaledInverseComplex<double, C> over_z(x, m);
    st.ox.h1[j] = over_x.split.h1, st.ox.h2[j] = over_x.split.h2, st.ox.lo[j] = over_x.split.lo;
    st.ozr.h1[j] = over_z.re.h1, st.ozr.h2[j] = over_z.re.h2, st.ozr.lo[j] = over_z.re.lo;
    st.ozi.h1[j] = over_z.im.h1, st.ozi.h2[j] = over_z.im.h2, st.ozi.lo[j] = over_z.im.lo;
    const C cd = (m - C(1.0)) * over_z(1.0);  // (m−1)/(m x), the δ recurrence's constant
    st.cdr[j] = cd.real(), st.cdi[j] = cd.imag();
    const C m_minus_1 = m - C(1.0);
    const C c = m_minus_1 * (m + C(1.0)) * recip(m);
    const C e = m_minus_1 * (m + C(1.0));
    st.mr[j] = m.real(), st.mi[j] = m.imag(), st.m1r[j] = m_minus_1.real(), st.m1i[j] = m_minus_1.imag();
    st.cr[j] = c.real(), st.ci[j] = c.imag(), st.er[j] = e.real(), st.ei[j] = e.imag();
    // 1/ξ₀ = sin x + i cos x; lane_series multiplies by ψ₁ (riccati_psi1).
    st.Rr[j] = std::sin(x), st.Ri[j] = std::cos(x);
  }
  // y_N(x) = 1/(ψ_N/ψ_{N+1}) and y_N(mx) at each lane's own N (downward_ratios),
  // where the lane starts from Lentz's value; zeros where it starts higher.
  st.yx0 = st.yzr0 = st.yzi0 = st.dr0 = st.di0 = V{};
  if (!any_lentz) return;
  const V order = st.Njd + 1.0;
  const LaneLentz lx(st.ox, nullptr, order), lz(st.ozr, &st.ozi, order);
  const V sz = 1 / (lz.fr * lz.fr + lz.fi * lz.fi);
  for (int j = 0; j < L; ++j) {
    if (miller[j] != 0) continue;
    st.yx0[j] = 1.0 / lx.fr[j];
    st.yzr0[j] = lz.fr[j] * sz[j], st.yzi0[j] = -lz.fi[j] * sz[j];
    st.dr0[j] = st.yzr0[j] - st.yx0[j], st.di0[j] = st.yzi0[j] - 0.0;  // yz − C(yx)
  }
}

// The downward pass: yₙ(x) and δₙ or yₙ(mx) (downward_ratios), each lane
// from its own table length.
ATTENUVIS_LANE_INLINE void lane_downward(const LaneState& st, LaneTables& tables) {
  const V zero{}, vtiny = splat((std::numeric_limits<double>::min)() * 1e20);
  V yx = st.yx0, yzr = st.yzr0, yzi = st.yzi0, dr = st.dr0, di = st.di0;
  for (std::size_t n = st.start;; --n) {
    const double k = double(2 * n + 1);
    const M start = st.start_d == double(n);  // the lane's own recurrence starts here
    yx = start ? st.yx0 : yx;
    yzr = start ? st.yzr0 : yzr, yzi = start ? st.yzi0 : yzi;
    dr = start ? st.dr0 : dr, di = start ? st.di0 : di;
    const M value = 64 * (yzr * yzr + yzi * yzi) < yx * yx;
    const M use_d = st.diff_slot & ~value;
    if (n <= st.N) {  // above: the Miller start's steps, not stored
      save(&tables.y[n * L], yx);
      save(&tables.w_re[n * L], use_d ? dr : yzr);
      save(&tables.w_im[n * L], use_d ? di : yzi);
      save(&tables.use_d[n * L], use_d);
    }
    if (n == 0) break;
    V den_x = st.ox.at(k) - yx;
    V dzr = st.ozr.at(k) - yzr, dzi = st.ozi.at(k) - yzi;
    den_x = den_x == zero ? vtiny : den_x;
    const M zero_z = (dzr == zero) & (dzi == zero);
    dzr = zero_z ? vtiny : dzr;
    dzi = zero_z ? zero : dzi;
    const V dnr = st.cdr * k + dr, dni = st.cdi * k + di;
    yx = 1 / den_x;
    const V sz = 1 / (dzr * dzr + dzi * dzi);
    yzr = dzr * sz, yzi = -dzi * sz;
    const V pr = dnr * yzr - dni * yzi, pi = dnr * yzi + dni * yzr;
    dr = pr * yx, di = pi * yx;
  }
}

// The series, order by order for all lanes (sum_series + term_block.hpp); one
// function because it mirrors sphere_terms/sum_terms formula by formula.
ATTENUVIS_LANE_INLINE void lane_series(LaneState& st, const LaneTables& tables, LaneResults& out) {
  const V zero{};
  const V x = st.x, Njd = st.Njd, mr = st.mr, mi = st.mi, m1r = st.m1r, m1i = st.m1i;
  const V cr = st.cr, ci = st.ci, er = st.er, ei = st.ei;
  const LaneInverse &ox = st.ox, &ozr = st.ozr, &ozi = st.ozi;
  const std::size_t N = st.N;
  // ψ₁/ξ₀ per lane, ψ₁ from y₀ as in sum_series (trap sin-zero); R₁ = ρ₁ ψ₁/ξ₀.
  V Rr = st.Rr, Ri = st.Ri, s = splat(1.0);
  for (int j = 0; j < L; ++j) {
    const double psi1 = riccati_psi1(st.Rr[j], st.Ri[j], tables.y[j], ScaledInverse<double>(st.x[j])(1.0));
    Rr[j] = st.Rr[j] * psi1, Ri[j] = st.Ri[j] * psi1;
  }
  // ---- the series, order by order for all lanes (sum_series + term_block) ----
  static const double tol = std::exp(-tail_log_tolerance<double>());
  LaneKahan ext, sca, abs_, back_re, back_im, g_cross, g_self;
  V rhor = zero, rhoi = splat(1.0), apr{}, api{}, bpr{}, bpi{};
  M active = zero == zero, converged_any = zero != zero;
  V terms = Njd;
  for (std::size_t n = 1; n <= N; ++n) {
    const double rn = double(n), wn = 2 * rn + 1, sign = n % 2 == 0 ? 1.0 : -1.0;
    // ρₙ = 1/((2n−1)/x − ρₙ₋₁) (HankelRatio), Rₙ, sₙ (pass 1).
    const V ur = ox.at(double(2 * n - 1)) - rhor, ui = 0.0 - rhoi;
    const V su = 1 / (ur * ur + ui * ui);
    rhor = ur * su, rhoi = -ui * su;
    const V t1r = Rr * rhor - Ri * rhoi, t1i = Rr * rhoi + Ri * rhor;
    const V yprev = n == 1 ? splat(1.0) : load<V>(&tables.y[(n - 1) * L]);
    Rr = t1r * yprev, Ri = t1i * yprev;
    s *= rhor * rhor + rhoi * rhoi;
    const V y_x = load<V>(&tables.y[n * L]);
    const M use_d = load<M>(&tables.use_d[n * L]);
    const V wr = load<V>(&tables.w_re[n * L]), wi = load<V>(&tables.w_im[n * L]);
    const V yr = use_d ? y_x + wr : wr, yi = use_d ? 0.0 + wi : wi;
    const V dyr = use_d ? wr : zero, dyi = use_d ? wi : zero;
    // aₙ, bₙ (sphere_terms in term_block.hpp).
    const V n_over_x = ox.at(rn), n1_over_x = ox.at(rn + 1), w_over_x = ox.at(2 * rn + 1);
    const V Gr = rhor - n_over_x, Gi = rhoi;
    const V cnr = cr * n1_over_x, cni = ci * n1_over_x;
    const V na_d_r = (m1r * y_x - dyr) - cnr, na_d_i = (m1i * y_x - dyi) - cni;
    const V nb_d_r = -(mr * dyr - mi * dyi) - m1r * y_x, nb_d_i = -(mr * dyi + mi * dyr) - m1i * y_x;
    const V na_v_r = (mr * y_x - yr) - cnr, na_v_i = (mi * y_x - yi) - cni;
    const V nb_v_r = y_x - (mr * yr - mi * yi), nb_v_i = 0.0 - (mr * yi + mi * yr);
    const V nar = use_d ? na_d_r : na_v_r, nai = use_d ? na_d_i : na_v_i;
    const V nbr = use_d ? nb_d_r : nb_v_r, nbi = use_d ? nb_d_i : nb_v_i;
    const V dmr = ozr.at(rn + 1) - yr, dmi = ozi.at(rn + 1) - yi;
    const V myr = mr * yr - mi * yi, myi = mr * yi + mi * yr;
    const V Ar = dmr - (mr * Gr - mi * Gi), Ai = dmi - (mr * Gi + mi * Gr);
    const V Br = (w_over_x - myr) - rhor, Bi = (0.0 - myi) - rhoi;
    const V sa = 1 / (Ar * Ar + Ai * Ai), sb = 1 / (Br * Br + Bi * Bi);
    const V iar = Ar * sa, iai = -Ai * sa, ibr = Br * sb, ibi = -Bi * sb;
    const V Rar = Rr * nar - Ri * nai, Rai = Rr * nai + Ri * nar;
    const V Rbr = Rr * nbr - Ri * nbi, Rbi = Rr * nbi + Ri * nbr;
    const V ar = Rar * iar - Rai * iai, ai = Rar * iai + Rai * iar;
    const V br = Rbr * ibr - Rbi * ibi, bi = Rbr * ibi + Rbi * ibr;
    const V im_t_a = dmi * mr - dmr * mi;
    const V alpha = -im_t_a * s * (iar * iar + iai * iai);
    const V beta = myi * s * (ibr * ibr + ibi * ibi);
    const V gdr = (rhor + y_x) - w_over_x, gdi = rhoi;
    const V p1r = Rr * er - Ri * ei, p1i = Rr * ei + Ri * er;
    const V p2r = p1r * dmr - p1i * dmi, p2i = p1r * dmi + p1i * dmr;
    const V p3r = p2r * gdr - p2i * gdi, p3i = p2r * gdi + p2i * gdr;
    const V p4r = p3r * iar - p3i * iai, p4i = p3r * iai + p3i * iar;
    const V ddr = p4r * ibr - p4i * ibi, ddi = p4r * ibi + p4i * ibr;
    const V sca_n = wn * ((ar * ar + ai * ai) + (br * br + bi * bi));
    const V abs_n = wn * (alpha + beta);
    // sum_terms
    const V back_r = sign * wn * ddr, back_i = sign * wn * ddi;
    const double inv_n = 1 / rn, inv_n1 = 1 / (rn + 1);
    const V gs = (inv_n + inv_n1) * (ar * br + ai * bi);
    const V gc = (rn - inv_n) * (apr * ar + api * ai + bpr * br + bpi * bi);
    const V size = wn * (vabs(ar) + vabs(ai) + vabs(br) + vabs(bi));
    apr = ar, api = ai, bpr = br, bpi = bi;
    // Compensated sums and the convergence test (pass 3).
    ext.add(sca_n + abs_n, active);
    sca.add(sca_n, active);
    abs_.add(abs_n, active);
    back_re.add(back_r, active);
    back_im.add(back_i, active);
    if (n >= 2) g_cross.add(gc, active);
    g_self.add(gs, active);
    const V e_abs = vabs(ext.sum), b_abs = vabs(back_re.sum) + vabs(back_im.sum);
    const V scale = b_abs < e_abs ? b_abs : e_abs;
    const M converged = active & (rn > x) & (size <= tol * scale);
    const M stop = active & (converged | (rn == Njd));
    converged_any |= converged;
    terms = stop ? splat(rn) : terms;
    active &= ~stop;
    bool any = false;
    for (int j = 0; j < L; ++j) any |= active[j] != 0;
    if (!any) break;
  }
  const V inv_x = 1.0 / x;
  const V f = 2.0 * inv_x * inv_x;
  const V br = back_re.value(), bi = back_im.value(), ssum = sca.value();
  const V qext = f * ext.value(), qsca = f * ssum, qabs = f * abs_.value();
  const V qback = (br * br + bi * bi) * inv_x * inv_x;
  const V g = ssum > zero ? 2.0 * (g_cross.value() + g_self.value()) / ssum : zero;
  const V qpr = qext - g * qsca;
  for (int j = 0; j < L; ++j) {
    Efficiencies<double>& q = out.q[j];
    q.terms = static_cast<std::size_t>(terms[j]);
    q.qext = qext[j], q.qsca = qsca[j], q.qabs = qabs[j], q.qback = qback[j], q.g = g[j], q.qpr = qpr[j];
    out.converged[j] = converged_any[j] != 0;
  }
}

ATTENUVIS_MIE_CLONES
void run_lanes(const LaneProblems& in, LaneResults& out) {
  LaneState st;
  lane_setup(in, st);
  thread_local LaneTables tables;
  tables.resize(st.N);
  lane_downward(st, tables);
  lane_series(st, tables, out);
}

}  // namespace

bool lane_eligible(double x, std::complex<double> m) {
  if (!size_parameter_error(x).empty() || !refractive_index_error(m).empty()) return false;
  if (use_extended(x, m, false, Options{})) return false;
  return choose_method<double, C>(x, m, max_terms<double>(x, std::cbrt(x))) == DMethod::downward;
}

void sphere_lanes(const LaneProblems& in, LaneResults& out) { run_lanes(in, out); }

}  // namespace attenuvis::mie::detail
