// The AVX-512 body of score_visible_block (visible_block.hpp), written with
// intrinsics: GCC's own vectorisation of the lane loops (visible_block.cpp)
// gathers the exp table entry by entry and shuffles scalars, three times
// slower.  Here the 32-entry table of 2^(j/32) sits in four registers and is
// read with two two-register permutes; each row is two vectors of 8 lanes.
//
// Every operation is the one of fixed_point_exp.hpp and build_packet, in
// the same order, without contraction into FMA (GCC would otherwise fuse
// the intrinsics' products and sums like any others): the same bits as the
// packets and the generic loops (tests/visgraph/test_visible_block.cpp).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include "visible_block_isa.hpp"

#ifdef ATTENUVIS_X86_DISPATCH

#include "fixed_point_exp.hpp"
#include "pair_packet.hpp"

#include <immintrin.h>

#include <algorithm>
#include <vector>

namespace attenuvis::visgraph::detail {

namespace {
#define ATTENUVIS_AVX512 __attribute__((target("avx512f"), always_inline))

struct ExpTable {
  __m512d q0, q1, q2, q3;  // entries 0-7, 8-15, 16-23, 24-31 of kExp2TableScaled
};

// Sums and maxima of the 8 lanes.  Here and below, the masked forms with a
// full mask: GCC 12 warns that the plain forms' undefined pass-through
// operand is uninitialised.
ATTENUVIS_AVX512 inline std::int64_t sum_lanes(__m512i v) {
  const __m256i s = _mm256_add_epi64(_mm512_maskz_extracti64x4_epi64(0xF, v, 0), _mm512_maskz_extracti64x4_epi64(0xF, v, 1));
  const __m128i t = _mm_add_epi64(_mm256_castsi256_si128(s), _mm256_extracti128_si256(s, 1));
  return _mm_cvtsi128_si64(t) + _mm_extract_epi64(t, 1);
}
ATTENUVIS_AVX512 inline double max_lanes(__m512d v) {
  const __m256d s = _mm256_max_pd(_mm512_maskz_extractf64x4_pd(0xF, v, 0), _mm512_maskz_extractf64x4_pd(0xF, v, 1));
  const __m128d t = _mm_max_pd(_mm256_castpd256_pd128(s), _mm256_extractf128_pd(s, 1));
  return std::max(_mm_cvtsd_f64(t), _mm_cvtsd_f64(_mm_unpackhi_pd(t, t)));
}

ATTENUVIS_AVX512 inline __m512i round_to_fixed(__m512d v) {
  const __m512d shifted = _mm512_add_pd(v, _mm512_set1_pd(kTwo52));
  return _mm512_sub_epi64(_mm512_castpd_si512(shifted), _mm512_set1_epi64(kTwo52Bits));
}

// scaled_exp (fixed_point_exp.hpp) on 8 lanes.
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
  const __m512i scaled_bits = _mm512_add_epi64(_mm512_castpd_si512(entry), _mm512_maskz_slli_epi64(0xFF, _mm512_maskz_srai_epi64(0xFF, n, 5), 52));
  return _mm512_mul_pd(_mm512_castsi512_pd(scaled_bits), p);
}

// One half (8 lanes) of a row: the pairs in sight, their distances (0 for
// the others).
struct Half {
  __mmask8 visible;
  __m512d distance;
};

struct Block {
  const double *bx, *by, *bz;  // 16 padded columns
  std::int64_t* col;           // col[s * 16 + l]
  double* col_max;             // 16 lanes, or null
};

ATTENUVIS_AVX512 inline Half half_row(const Block& b, int h, __m512d ox, __m512d oy, __m512d oz, __mmask8 active,
                                      double max_distance, std::uint64_t& coincident) {
  const __m512d dx = _mm512_sub_pd(_mm512_load_pd(b.bx + 8 * h), ox);
  const __m512d dy = _mm512_sub_pd(_mm512_load_pd(b.by + 8 * h), oy);
  const __m512d dz = _mm512_sub_pd(_mm512_load_pd(b.bz + 8 * h), oz);
  const __m512d d = _mm512_maskz_sqrt_pd(
      0xFF, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz)));
  const __mmask8 apart = _mm512_cmp_pd_mask(d, _mm512_set1_pd(kCoincident), _CMP_GE_OQ);
  const __mmask8 within = _mm512_cmp_pd_mask(d, _mm512_set1_pd(max_distance), _CMP_LE_OQ);
  coincident += static_cast<std::uint64_t>(__builtin_popcount(active & static_cast<__mmask8>(~apart)));
  const __mmask8 visible = active & apart & within;
  return Half{visible, _mm512_maskz_mov_pd(visible, d)};
}

// Row totals of one row against the block's columns: degree, distance, one
// per sigma (row_total), column totals added in place.
ATTENUVIS_AVX512 inline void score_row(const Block& b, const double* row_xyz, __mmask16 active, const double* neg_sigma,
                                       int K, double max_distance, const ExpTable& table, std::int64_t* row_total,
                                       double& row_max, BlockCounts& counts) {
  const __m512d ox = _mm512_set1_pd(row_xyz[0]), oy = _mm512_set1_pd(row_xyz[1]), oz = _mm512_set1_pd(row_xyz[2]);
  const Half half[2] = {
      half_row(b, 0, ox, oy, oz, static_cast<__mmask8>(active & 0xFF), max_distance, counts.coincident),
      half_row(b, 1, ox, oy, oz, static_cast<__mmask8>(active >> 8), max_distance, counts.coincident)};
  const __m512i one = _mm512_set1_epi64(1);
  __m512i degree = _mm512_setzero_si512(), distance = _mm512_setzero_si512();
  for (int h = 0; h < 2; ++h) {
    __m512i* col_degree = reinterpret_cast<__m512i*>(b.col + 8 * h);
    __m512i* col_distance = reinterpret_cast<__m512i*>(b.col + 16 + 8 * h);
    const __m512i v = _mm512_maskz_mov_epi64(half[h].visible, one);
    const __m512i f = round_to_fixed(_mm512_mul_pd(half[h].distance, _mm512_set1_pd(kDistanceScale)));
    degree = _mm512_add_epi64(degree, v);
    distance = _mm512_add_epi64(distance, f);
    _mm512_store_si512(col_degree, _mm512_add_epi64(_mm512_load_si512(col_degree), v));
    _mm512_store_si512(col_distance, _mm512_add_epi64(_mm512_load_si512(col_distance), f));
    if (b.col_max) {
      _mm512_store_pd(b.col_max + 8 * h,
                      _mm512_maskz_max_pd(0xFF, _mm512_load_pd(b.col_max + 8 * h), half[h].distance));
      row_max = std::max(row_max, max_lanes(half[h].distance));
    }
  }
  const std::int64_t row_degree = sum_lanes(degree);
  counts.visible += static_cast<std::uint64_t>(row_degree);
  row_total[0] += row_degree;
  row_total[1] += sum_lanes(distance);
  for (int k = 0; k < K; ++k) {
    const __m512d s = _mm512_set1_pd(neg_sigma[k]);
    __m512i sum = _mm512_setzero_si512();
    for (int h = 0; h < 2; ++h) {
      const __m512d x =
          _mm512_maskz_max_pd(0xFF, _mm512_mul_pd(s, half[h].distance), _mm512_set1_pd(kLowestArgument));
      const __m512i c = round_to_fixed(_mm512_maskz_mov_pd(half[h].visible, scaled_exp8(x, table)));
      __m512i* col = reinterpret_cast<__m512i*>(b.col + 16 * (2 + k) + 8 * h);
      _mm512_store_si512(col, _mm512_add_epi64(_mm512_load_si512(col), c));
      sum = _mm512_add_epi64(sum, c);
    }
    row_total[2 + k] += sum_lanes(sum);
  }
}
}  // namespace

__attribute__((target("avx512f"))) BlockCounts score_visible_block_avx512(
    const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma, int K, double max_distance,
    std::int64_t* acc, std::size_t N, double* max_distance_of) {
  alignas(64) double bx[kLanes] = {}, by[kLanes] = {}, bz[kLanes] = {}, col_max[kLanes] = {};
  for (int l = 0; l < cols.count; ++l) {
    bx[l] = cols.x[cols.first + static_cast<std::size_t>(l)];
    by[l] = cols.y[cols.first + static_cast<std::size_t>(l)];
    bz[l] = cols.z[cols.first + static_cast<std::size_t>(l)];
  }
  const std::size_t slots = 2 + static_cast<std::size_t>(K);
  std::vector<std::int64_t> heap;
  alignas(64) std::int64_t col_stack[(2 + 8) * kLanes];
  std::int64_t row_stack[2 + 8];
  if (slots > 2 + 8) heap.assign(slots * (kLanes + 1) + 8, 0);
  // The heap block's columns start on a 64-byte boundary.
  std::int64_t* heap_col = heap.empty() ? nullptr
      : heap.data() + (8 - (reinterpret_cast<std::uintptr_t>(heap.data()) / sizeof(std::int64_t)) % 8) % 8;
  std::int64_t* col = heap.empty() ? col_stack : heap_col;
  std::int64_t* row_total = heap.empty() ? row_stack : heap_col + slots * kLanes;
  std::fill(col, col + slots * kLanes, 0);
  const Block b{bx, by, bz, col, max_distance_of ? col_max : nullptr};
  const ExpTable table{_mm512_loadu_pd(kExp2TableScaled.v), _mm512_loadu_pd(kExp2TableScaled.v + 8),
                       _mm512_loadu_pd(kExp2TableScaled.v + 16), _mm512_loadu_pd(kExp2TableScaled.v + 24)};
  const __mmask16 columns = static_cast<__mmask16>((1u << cols.count) - 1u);
  BlockCounts counts;
  for (int a = 0; a < rows.count; ++a) {
    const std::size_t i = rows.first + static_cast<std::size_t>(a);
    const __mmask16 active = same ? static_cast<__mmask16>(columns & ~((2u << a) - 1u)) : columns;
    std::fill(row_total, row_total + slots, 0);
    double row_max = 0;
    const double xyz[3] = {rows.x[i], rows.y[i], rows.z[i]};
    score_row(b, xyz, active, neg_sigma, K, max_distance, table, row_total, row_max, counts);
    for (std::size_t s = 0; s < slots; ++s) acc[s * N + i] += row_total[s];
    if (max_distance_of) max_distance_of[i] = std::max(max_distance_of[i], row_max);
  }
  for (int l = 0; l < cols.count; ++l) {
    const std::size_t j = cols.first + static_cast<std::size_t>(l);
    for (std::size_t s = 0; s < slots; ++s) acc[s * N + j] += col[s * kLanes + static_cast<std::size_t>(l)];
    if (max_distance_of) max_distance_of[j] = std::max(max_distance_of[j], col_max[l]);
  }
  return counts;
}

}  // namespace attenuvis::visgraph::detail

#endif  // ATTENUVIS_X86_DISPATCH
