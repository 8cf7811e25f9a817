// scaled_exp (fixed_point_exp.hpp) on eight lanes with AVX-512 intrinsics,
// for the kernels that score pairs (visible_block_avx512.cpp: blocks in
// sight; contrast_kernel_avx512.cpp: packets after their rays).  GCC's own
// vectorisation of the scalar body gathers the table entry by entry and
// shuffles scalars, about three times slower; here the 32-entry table of
// 2^(j/32) sits in four registers and is read with two two-register permutes.
// Internal to the visgraph library.
//
// Every operation is the scalar body's, in the same order.  Files that
// include this header must switch floating-point contraction off, as the
// scalar kernels do: GCC would otherwise fuse the intrinsics' products and
// sums like any others, and the bits would differ from the other paths.
#pragma once

#include "lane_isa.hpp"

#ifdef ATTENUVIS_X86_DISPATCH

#include "fixed_point_exp.hpp"

#include <immintrin.h>

#include <cstdint>

namespace attenuvis::visgraph::detail {

#define ATTENUVIS_AVX512 __attribute__((target("avx512f"), always_inline))

struct ExpTable {
  __m512d q0, q1, q2, q3;  // entries 0-7, 8-15, 16-23, 24-31 of kExp2TableScaled
};

ATTENUVIS_AVX512 inline ExpTable load_exp_table() {
  return ExpTable{_mm512_loadu_pd(kExp2TableScaled.v), _mm512_loadu_pd(kExp2TableScaled.v + 8),
                  _mm512_loadu_pd(kExp2TableScaled.v + 16), _mm512_loadu_pd(kExp2TableScaled.v + 24)};
}

// round_fixed on 8 lanes.
ATTENUVIS_AVX512 inline __m512i round_to_fixed(__m512d v) {
  const __m512d shifted = _mm512_add_pd(v, _mm512_set1_pd(kTwo52));
  return _mm512_sub_epi64(_mm512_castpd_si512(shifted), _mm512_set1_epi64(kTwo52Bits));
}

// scaled_exp on 8 lanes.  The shifts are the masked forms with a full mask:
// GCC 12 warns that the plain forms' undefined pass-through operand is
// uninitialised.
ATTENUVIS_AVX512 inline __m512d scaled_exp8(__m512d x, const ExpTable& table) {
  const __m512d t = _mm512_add_pd(_mm512_mul_pd(x, _mm512_set1_pd(k32ByLn2)), _mm512_set1_pd(kShifter));
  const __m512i n = _mm512_sub_epi64(_mm512_castpd_si512(t), _mm512_set1_epi64(kShifterBits));
  const __m512d dn = _mm512_sub_pd(t, _mm512_set1_pd(kShifter));
  const __m512d r = _mm512_sub_pd(_mm512_sub_pd(x, _mm512_mul_pd(dn, _mm512_set1_pd(kLn2By32Hi))),
                                  _mm512_mul_pd(dn, _mm512_set1_pd(kLn2By32Lo)));
  __m512d p = _mm512_set1_pd(1.0 / 720.0);
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(1.0 / 120.0));
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(1.0 / 24.0));
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(1.0 / 6.0));
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(0.5));
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(1.0));
  p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(1.0));
  // Entry n & 31: bits 0-3 pick within a pair of registers, bit 4 the pair.
  const __m512d low = _mm512_permutex2var_pd(table.q0, n, table.q1);
  const __m512d high = _mm512_permutex2var_pd(table.q2, n, table.q3);
  const __mmask8 upper = _mm512_test_epi64_mask(n, _mm512_set1_epi64(16));
  const __m512d entry = _mm512_mask_blend_pd(upper, low, high);
  const __m512i scaled_bits = _mm512_add_epi64(_mm512_castpd_si512(entry),
                                               _mm512_maskz_slli_epi64(0xFF, _mm512_maskz_srai_epi64(0xFF, n, 5), 52));
  return _mm512_mul_pd(_mm512_castsi512_pd(scaled_bits), p);
}

}  // namespace attenuvis::visgraph::detail

#endif  // ATTENUVIS_X86_DISPATCH
