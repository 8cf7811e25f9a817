// kLanes spheres at once, one per vector lane: see sphere_lanes.hpp.  The
// scalar set-up and finish are here; the vector kernels (plain arithmetic on
// GCC vectors of one register) are in sphere_lanes_kernels.inc, compiled once
// per instruction set and chosen at run time; each lane's operations are
// those of series.hpp.
#include "sphere_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "series.hpp"
#include "sphere_checks.hpp"

namespace attenuvis::mie::detail {
namespace {

constexpr int L = kLanes;
using C = std::complex<double>;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr double kTiny = (std::numeric_limits<double>::min)() * 1e20;  // avoid_zero()'s stand-in

// The per-lane data of a group, lane j at index j of each array (the kernels
// load them a register at a time).
// k/x or one part of k/(mx) per lane: the split constants of SplitInverse.
struct LaneInverse {
  alignas(64) double h1[L], h2[L], lo[L];
};

// Per-lane constants (as mie_series/sum_series/downward_ratios).
struct LaneState {
  std::size_t N = 0;      // longest table of the lanes
  std::size_t start = 0;  // highest start index of the downward pass
  double tol = 0;         // relative size of the last term kept (tail_log_tolerance)
  alignas(64) double x[L], inv_x[L], Njd[L], start_d[L], mr[L], mi[L], m1r[L], m1i[L], cr[L], ci[L], er[L], ei[L],
      cdr[L], cdi[L], Rr[L], Ri[L];
  alignas(64) long long diff_slot[L], lentz[L];  // δ slot; downward pass started from Lentz's value (not Miller's)
  LaneInverse ox{}, ozr{}, ozi{};
};

// The per-lane sums the series ends with.
struct LaneSums {
  alignas(64) double ext[L], sca[L], abs[L], back_re[L], back_im[L], g_cross[L], g_self[L], terms[L];
  alignas(64) long long converged[L];
};

// Per-thread tables of the downward pass, one vector per order n, in plain
// double arrays (std::vector of an over-aligned vector type was not aligned
// by this standard library); the kernels load and store through memcpy.
struct LaneTables {
  std::vector<double> y, w_re, w_im, use_d;
  void resize(std::size_t N) {
    const std::size_t n = (N + 1) * L;
    if (y.size() < n) y.resize(n), w_re.resize(n), w_im.resize(n), use_d.resize(n);
  }
};
struct LaneTablePointers {
  double *y, *w_re, *w_im, *use_d;
};

}  // namespace

// The kernels, once per instruction set (see sphere_lanes_kernels.inc for why
// not target_clones).  All three give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define ATTENUVIS_MIE_LANE_ISAS 1
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
namespace {
namespace avx512 {
#define ATTENUVIS_LANE_WIDTH 8
#include "sphere_lanes_kernels.inc"
#undef ATTENUVIS_LANE_WIDTH
}  // namespace avx512
}  // namespace
#pragma GCC pop_options
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
namespace {
namespace avx2 {
#define ATTENUVIS_LANE_WIDTH 4
#include "sphere_lanes_kernels.inc"
#undef ATTENUVIS_LANE_WIDTH
}  // namespace avx2
}  // namespace
#pragma GCC pop_options
#endif
namespace {
namespace generic {
#define ATTENUVIS_LANE_WIDTH 2
#include "sphere_lanes_kernels.inc"
#undef ATTENUVIS_LANE_WIDTH
}  // namespace generic

struct LaneKernels {
  const char* name;
  bool (*start_and_downward)(const LaneState&, const LaneTablePointers&, const LaneState*, const LaneTablePointers*);
  void (*series)(const LaneState&, const LaneTablePointers&, LaneSums&);
};

// The kernels this CPU can run, best first.
std::vector<LaneKernels> find_kernels() {
  std::vector<LaneKernels> k;
#ifdef ATTENUVIS_MIE_LANE_ISAS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) k.push_back({"avx512", avx512::start_and_downward, avx512::series});
  if (__builtin_cpu_supports("x86-64-v3")) k.push_back({"avx2", avx2::start_and_downward, avx2::series});
#endif
  k.push_back({"generic", generic::start_and_downward, generic::series});
  return k;
}

const std::vector<LaneKernels>& kernels() {
  static const std::vector<LaneKernels> k = find_kernels();
  return k;
}

// Per-lane constants; the start of each lane's downward pass: Lentz at N, or
// zeros at N + K (miller_depth).
void lane_setup(const LaneProblems& in, LaneState& st) {
  st.tol = std::exp(-tail_log_tolerance<double>());
  for (int j = 0; j < L; ++j) {
    st.x[j] = in.x[j];
    const double x = in.x[j];
    const C m = in.m[j];
    const std::size_t Nj = in.terms[j];  // first_terms(x), from lane_terms()
    st.N = std::max(st.N, Nj);
    st.Njd[j] = double(Nj);
    const std::size_t miller = miller_depth(x, m, Nj);
    st.start = std::max(st.start, Nj + miller);
    st.start_d[j] = double(Nj + miller);
    st.lentz[j] = miller == 0 ? -1 : 0;
    const C dm = m - 1.0;
    st.diff_slot[j] = norm2(dm) < 0.25 ? -1 : 0;
    const ScaledInverse<double> over_x(x);
    const ScaledInverseComplex<double, C> over_z(x, m);
    st.inv_x[j] = over_x(1.0);
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
  }
}

// ψ₁/ξ₀ per lane (1/ξ₀ = sin x + i cos x), ψ₁ from y₀ as in sum_series (trap
// sin-zero); R₁ = ρ₁ ψ₁/ξ₀ is formed in the series.
void lane_psi1(const LaneTables& tables, LaneState& st) {
  for (int j = 0; j < L; ++j) {
    const double x = st.x[j], sx = std::sin(x), cx = std::cos(x);
    const double psi1 = riccati_psi1(sx, cx, tables.y[j], st.inv_x[j]);
    st.Rr[j] = sx * psi1, st.Ri[j] = cx * psi1;
  }
}

// The efficiencies from the sums (SeriesSums::finish), lane by lane.
void lane_finish(const LaneState& st, const LaneSums& s, LaneResults& out) {
  for (int j = 0; j < L; ++j) {
    Efficiencies<double>& q = out.q[j];
    const double inv_x = 1.0 / st.x[j];
    const double f = 2.0 * inv_x * inv_x;
    const double br = s.back_re[j], bi = s.back_im[j], ssum = s.sca[j];
    q.terms = static_cast<std::size_t>(s.terms[j]);
    q.qext = f * s.ext[j];
    q.qsca = f * ssum;
    q.qabs = f * s.abs[j];
    q.qback = (br * br + bi * bi) * inv_x * inv_x;
    q.g = ssum > 0 ? 2.0 * (s.g_cross[j] + s.g_self[j]) / ssum : 0.0;
    q.qpr = q.qext - q.g * q.qsca;
    out.converged[j] = s.converged[j] != 0;
  }
}

}  // namespace

std::vector<std::string> lane_instruction_sets() {
  std::vector<std::string> names;
  for (const auto& k : kernels()) names.push_back(k.name);
  return names;
}

int lane_kernel_index(const std::string& name) {
  if (name.empty()) return 0;
  const auto& k = kernels();
  for (std::size_t i = 0; i < k.size(); ++i)
    if (name == k[i].name) return static_cast<int>(i);
  return -1;
}

bool lane_eligible(double x, std::complex<double> m) {
  if (!size_parameter_error(x).empty() || !refractive_index_error(m).empty()) return false;
  return lane_terms(x, m) > 0;
}

std::size_t lane_terms(double x, std::complex<double> m) {
  const double cbrt_x = bound_cbrt(x);  // as mie_series, so the table lengths agree
  if (use_extended(x, m, false, Options{})) return 0;
  if (choose_method<double, C>(x, m, max_terms<double>(x, cbrt_x)) != DMethod::downward) return 0;
  return first_terms<double>(x, cbrt_x);
}

void sphere_lanes(const LaneProblems* in, LaneResults* out, int groups, int kernel) {
  const LaneKernels& k = kernels().at(static_cast<std::size_t>(kernel));
  LaneState st[2];
  thread_local LaneTables tables[2];
  LaneTablePointers p[2];
  for (int g = 0; g < groups; ++g) {
    lane_setup(in[g], st[g]);
    tables[g].resize(st[g].N);
    p[g] = {tables[g].y.data(), tables[g].w_re.data(), tables[g].w_im.data(), tables[g].use_d.data()};
  }
  if (!k.start_and_downward(st[0], p[0], groups > 1 ? &st[1] : nullptr, groups > 1 ? &p[1] : nullptr))
    throw std::runtime_error("attenuvis::mie: Lentz continued fraction did not converge");
  for (int g = 0; g < groups; ++g) {
    lane_psi1(tables[g], st[g]);
    LaneSums sums;
    k.series(st[g], p[g], sums);
    lane_finish(st[g], sums, out[g]);
  }
}

}  // namespace attenuvis::mie::detail
