// The AVX-512 body of contrast_lanes (contrast_kernel.hpp): the 16 lanes as
// two vectors of 8, each sigma's exp by scaled_exp8 (exp_avx512.hpp).
//
// Every operation is the portable body's (contrast_kernel.cpp), in the same
// order, without contraction into FMA: the same bits
// (tests/visgraph/test_contrast_kernel.cpp compares the variants).  The
// visibility factor multiplies, as there, rather than masks: 1.0 and 0.0
// give the same values either way, and the same operations leave no doubt.
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include "contrast_kernel_isa.hpp"

#ifdef ATTENUVIS_X86_DISPATCH

#include "exp_avx512.hpp"

#include <immintrin.h>

namespace attenuvis::visgraph::detail {

__attribute__((target("avx512f"))) void contrast_lanes_avx512(const double* distance, const double* visible,
                                                             const double* neg_sigma, int K, std::int64_t* c_fixed,
                                                             std::int64_t* d_fixed) {
  static_assert(kLanes == 16, "two vectors of 8 lanes");
  const ExpTable table = load_exp_table();
  const __m512d d0 = _mm512_loadu_pd(distance), d1 = _mm512_loadu_pd(distance + 8);
  const __m512d v0 = _mm512_loadu_pd(visible), v1 = _mm512_loadu_pd(visible + 8);
  const __m512d scale = _mm512_set1_pd(kDistanceScale);
  _mm512_storeu_si512(d_fixed, round_to_fixed(_mm512_mul_pd(_mm512_mul_pd(v0, d0), scale)));
  _mm512_storeu_si512(d_fixed + 8, round_to_fixed(_mm512_mul_pd(_mm512_mul_pd(v1, d1), scale)));
  const __m512d lowest = _mm512_set1_pd(kLowestArgument);
  for (int k = 0; k < K; ++k) {
    // max(s d, -700) as the portable clamp: s d < -700 ? -700 : s d.
    const __m512d s = _mm512_set1_pd(neg_sigma[k]);
    const __m512d x0 = _mm512_maskz_max_pd(0xFF, _mm512_mul_pd(s, d0), lowest);
    const __m512d x1 = _mm512_maskz_max_pd(0xFF, _mm512_mul_pd(s, d1), lowest);
    std::int64_t* c = c_fixed + k * kLanes;
    _mm512_storeu_si512(c, round_to_fixed(_mm512_mul_pd(scaled_exp8(x0, table), v0)));
    _mm512_storeu_si512(c + 8, round_to_fixed(_mm512_mul_pd(scaled_exp8(x1, table), v1)));
  }
}

}  // namespace attenuvis::visgraph::detail

#endif  // ATTENUVIS_X86_DISPATCH
