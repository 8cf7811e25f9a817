// The per-pair exp is the bottleneck once rays come 16 at a time, so it is
// written as branch-free loops over the 16 lanes that the compiler turns
// into SIMD code, compiled for AVX-512, AVX2 and baseline x86-64 and picked
// at run time (GCC target_clones).  GCC contracts a*b+c into FMA by default
// in C++ (-ffp-contract=fast outside ISO C modes) wherever the target has
// FMA, which the AVX-512 clone does: contraction is switched off for this
// file so that every clone computes bit-identical results (clang's default
// contracts only within one expression, and its pragma says off as well).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include "fixed_point_exp.hpp"

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
}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void contrast_lanes(const double* distance, const double* visible, const double* neg_sigma, int K,
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

}  // namespace attenuvis::visgraph::detail
