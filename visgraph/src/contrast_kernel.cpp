// The per-pair exp is the bottleneck once rays come 16 at a time.  The
// portable body is written as branch-free loops over the 16 lanes that the
// compiler turns into SIMD code, compiled for AVX2 and baseline x86-64.
// AVX-512 has a body of its own with intrinsics (contrast_kernel_avx512.cpp):
// GCC's AVX-512 code for the portable body read the exp table entry by
// entry; the whole kernel took 1.8 times as long (12 % of layout 1's profile
// against 7 %).  The widest the CPU runs is picked once.
//
// GCC contracts a*b+c into FMA by default in C++ (-ffp-contract=fast outside
// ISO C modes) wherever the target has FMA: contraction is switched off for
// this file so that every variant computes bit-identical results (clang's
// default contracts only within one expression, and its pragma says off as
// well).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include "contrast_kernel_isa.hpp"
#include "fixed_point_exp.hpp"

#include <optional>

namespace attenuvis::visgraph::detail {

namespace {
// At most this many (sigma, lane) values go through one flat loop: four
// sigmas of a packet, so that the out-of-order core overlaps their
// independent polynomial chains.
constexpr int kBlock = 4 * kLanes;

// Round non-negative values below 2^52 to the nearest integer (ties to even).
inline void round_to_int64(const double* value, std::int64_t* out, int count) {
  for (int l = 0; l < count; ++l) out[l] = round_fixed(value[l]);
}

inline void contrast_body(const double* distance, const double* visible, const double* neg_sigma, int K,
                          std::int64_t* c_fixed, std::int64_t* d_fixed) {
  alignas(64) double scaled[kLanes];
  for (int l = 0; l < kLanes; ++l) scaled[l] = visible[l] * distance[l] * kDistanceScale;
  round_to_int64(scaled, d_fixed, kLanes);

  for (int k0 = 0; k0 < K; k0 += kBlock / kLanes) {
    const int m = (K - k0 < kBlock / kLanes ? K - k0 : kBlock / kLanes) * kLanes;
    alignas(64) double x[kBlock], vis[kBlock], result[kBlock];
    for (int e = 0; e < m; e += kLanes) {
      const double s = neg_sigma[k0 + e / kLanes];
      for (int l = 0; l < kLanes; ++l) {
        const double v = s * distance[l];
        x[e + l] = v < kLowestArgument ? kLowestArgument : v;
        vis[e + l] = visible[l];
      }
    }
    for (int e = 0; e < m; ++e) result[e] = scaled_exp(x[e]) * vis[e];
    round_to_int64(result, c_fixed + k0 * kLanes, m);
  }
}

using ContrastFunction = void (*)(const double*, const double*, const double*, int, std::int64_t*, std::int64_t*);

#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target("avx2"), flatten)) void contrast_avx2(const double* distance, const double* visible,
                                                            const double* neg_sigma, int K, std::int64_t* c_fixed,
                                                            std::int64_t* d_fixed) {
  contrast_body(distance, visible, neg_sigma, K, c_fixed, d_fixed);
}
#endif
__attribute__((flatten)) void contrast_baseline(const double* distance, const double* visible,
                                                const double* neg_sigma, int K, std::int64_t* c_fixed,
                                                std::int64_t* d_fixed) {
  contrast_body(distance, visible, neg_sigma, K, c_fixed, d_fixed);
}

ContrastFunction contrast_function(Isa isa) {
#ifdef ATTENUVIS_X86_DISPATCH
  if (isa == Isa::avx512) return contrast_lanes_avx512;
  if (isa == Isa::avx2) return contrast_avx2;
#endif
  (void)isa;
  return contrast_baseline;
}
}  // namespace

void contrast_lanes(const double* distance, const double* visible, const double* neg_sigma, int K,
                    std::int64_t* c_fixed, std::int64_t* d_fixed) {
  static const ContrastFunction chosen = contrast_function(pick_isa());
  chosen(distance, visible, neg_sigma, K, c_fixed, d_fixed);
}

bool contrast_lanes_with(int instruction_set, const double* distance, const double* visible, const double* neg_sigma,
                         int K, std::int64_t* c_fixed, std::int64_t* d_fixed) {
  const std::optional<Isa> isa = isa_numbered(instruction_set);
  if (!isa) return false;
  contrast_function(*isa)(distance, visible, neg_sigma, K, c_fixed, d_fixed);
  return true;
}

}  // namespace attenuvis::visgraph::detail
