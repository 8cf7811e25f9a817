// The AVX-512 body of score_visible_block (visible_block.hpp), written with
// intrinsics around scaled_exp8 (exp_avx512.hpp): GCC's own vectorisation
// of the lane loops (visible_block.cpp) is three times slower.  Each row is
// two vectors of 8 lanes.
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

#include "exp_avx512.hpp"
#include "pair_packet.hpp"

#include <immintrin.h>

#include <algorithm>

namespace attenuvis::visgraph::detail {

namespace {
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

// Columns are taken 8 at a time, straight from the contiguous coordinate
// and accumulator arrays; a tile of columns (their coordinates and
// accumulator slots stay in L1) is run through by every row in turn, and a
// row's totals are reduced once per tile.
constexpr int kTile = 256;

// What a chunk of sigmas is asked to do.
struct Chunk {
  double max_distance;
  bool first;      // also counts degree, coincident pairs, distance sums and maxima
  bool distances;  // distance sums and maxima (distance statistics)
  const double* neg_sigma;
  int k0;          // its sigmas are neg_sigma[0 ..), slots 2 + k0 ..
};

// Eight columns against one row: the pairs in sight and their distances (0
// for the others).
struct Lanes {
  __mmask8 visible;
  __m512d distance;
};

ATTENUVIS_AVX512 inline Lanes eight_columns(const BlockSide& cols, std::size_t j, __mmask8 real, __m512d ox,
                                            __m512d oy, __m512d oz, double max_distance, int& coincident) {
  const __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(real, cols.x + j), ox);
  const __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(real, cols.y + j), oy);
  const __m512d dz = _mm512_sub_pd(_mm512_maskz_loadu_pd(real, cols.z + j), oz);
  const __m512d d = _mm512_maskz_sqrt_pd(
      0xFF, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz)));
  const __mmask8 apart = _mm512_cmp_pd_mask(d, _mm512_set1_pd(kCoincident), _CMP_GE_OQ);
  const __mmask8 within = _mm512_cmp_pd_mask(d, _mm512_set1_pd(max_distance), _CMP_LE_OQ);
  coincident = __builtin_popcount(real & static_cast<__mmask8>(~apart));
  const __mmask8 visible = real & apart & within;
  return Lanes{visible, _mm512_maskz_mov_pd(visible, d)};
}

// acc[j .. j + 8) += v on the real lanes.
ATTENUVIS_AVX512 inline void add_to(std::int64_t* at, __mmask8 real, __m512i v) {
  _mm512_mask_storeu_epi64(at, real, _mm512_add_epi64(_mm512_maskz_loadu_epi64(real, at), v));
}

// A row's totals over one tile.
template <int KC>
struct RowTotals {
  std::int64_t degree;
  __m512i distance;
  __m512d farthest;
  __m512i c[KC > 0 ? KC : 1];
};

// Row i against columns [j, j + 8) (real lanes): their credits in place,
// the row's in `row`.
template <int KC>
ATTENUVIS_AVX512 inline void score_lanes(const BlockSide& cols, std::size_t j, __mmask8 real, const double* o,
                                         const Chunk& chunk, const ExpTable& table, std::int64_t* acc, std::size_t N,
                                         double* max_distance_of, RowTotals<KC>& row, BlockCounts& counts) {
  int coincident = 0;
  const Lanes lanes = eight_columns(cols, j, real, _mm512_set1_pd(o[0]), _mm512_set1_pd(o[1]), _mm512_set1_pd(o[2]),
                                    chunk.max_distance, coincident);
  if (chunk.first) {
    counts.coincident += static_cast<std::uint64_t>(coincident);
    row.degree += __builtin_popcount(lanes.visible);
    _mm512_mask_storeu_epi64(acc + j, lanes.visible,
                             _mm512_add_epi64(_mm512_maskz_loadu_epi64(lanes.visible, acc + j), _mm512_set1_epi64(1)));
    if (chunk.distances) {
      const __m512i f = round_to_fixed(_mm512_mul_pd(lanes.distance, _mm512_set1_pd(kDistanceScale)));
      row.distance = _mm512_add_epi64(row.distance, f);
      add_to(acc + N + j, real, f);
      row.farthest = _mm512_maskz_max_pd(0xFF, row.farthest, lanes.distance);
      double* m = max_distance_of + j;
      _mm512_mask_storeu_pd(m, real, _mm512_maskz_max_pd(0xFF, _mm512_maskz_loadu_pd(real, m), lanes.distance));
    }
  }
  for (int k = 0; k < KC; ++k) {
    const __m512d x = _mm512_maskz_max_pd(0xFF, _mm512_mul_pd(_mm512_set1_pd(chunk.neg_sigma[k]), lanes.distance),
                                          _mm512_set1_pd(kLowestArgument));
    const __m512i v = round_to_fixed(_mm512_maskz_mov_pd(lanes.visible, scaled_exp8(x, table)));
    row.c[k] = _mm512_add_epi64(row.c[k], v);
    add_to(acc + static_cast<std::size_t>(2 + chunk.k0 + k) * N + j, real, v);
  }
}

// The rows against columns [from, to) of cols (same: the pairs a < b of
// one leaf), for the sigmas of `chunk`.
template <int KC>
ATTENUVIS_AVX512 inline void score_tile(const BlockSide& rows, const BlockSide& cols, bool same, std::size_t from,
                                        std::size_t to, const Chunk& chunk, const ExpTable& table, std::int64_t* acc,
                                        std::size_t N, double* max_distance_of, BlockCounts& counts) {
  for (int a = 0; a < rows.count; ++a) {
    const std::size_t i = rows.first + static_cast<std::size_t>(a);
    const double o[3] = {rows.x[i], rows.y[i], rows.z[i]};
    RowTotals<KC> row;
    row.degree = 0;
    row.distance = _mm512_setzero_si512();
    row.farthest = _mm512_setzero_pd();
    for (int k = 0; k < KC; ++k) row.c[k] = _mm512_setzero_si512();
    const std::size_t start = same ? std::max(from, i + 1) : from;
    for (std::size_t j = start; j < to; j += 8) {
      const __mmask8 real = static_cast<__mmask8>(to - j >= 8 ? 0xFF : (1u << (to - j)) - 1u);
      score_lanes<KC>(cols, j, real, o, chunk, table, acc, N, max_distance_of, row, counts);
    }
    if (chunk.first) {
      counts.visible += static_cast<std::uint64_t>(row.degree);
      acc[i] += row.degree;
      if (chunk.distances) {
        acc[N + i] += sum_lanes(row.distance);
        max_distance_of[i] = std::max(max_distance_of[i], max_lanes(row.farthest));
      }
    }
    for (int k = 0; k < KC; ++k) acc[static_cast<std::size_t>(2 + chunk.k0 + k) * N + i] += sum_lanes(row.c[k]);
  }
}

template <int KC>
ATTENUVIS_AVX512 inline void score_chunk(const BlockSide& rows, const BlockSide& cols, bool same, const Chunk& chunk,
                                         const ExpTable& table, std::int64_t* acc, std::size_t N,
                                         double* max_distance_of, BlockCounts& counts) {
  const std::size_t end = cols.first + static_cast<std::size_t>(cols.count);
  for (std::size_t from = cols.first; from < end; from += kTile)
    score_tile<KC>(rows, cols, same, from, std::min(end, from + kTile), chunk, table, acc, N, max_distance_of, counts);
}
}  // namespace

__attribute__((target("avx512f"))) BlockCounts score_visible_block_avx512(
    const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma, int K, double max_distance,
    std::int64_t* acc, std::size_t N, double* max_distance_of) {
  const ExpTable table = load_exp_table();
  BlockCounts counts;
  // Sigmas four at a time (the distances are recomputed per chunk, a small
  // part of four exps); the first chunk also does the counts.
  Chunk chunk{max_distance, true, max_distance_of != nullptr, neg_sigma, 0};
  do {
    const int n = std::min(4, K - chunk.k0);
    switch (n) {
      case 4: score_chunk<4>(rows, cols, same, chunk, table, acc, N, max_distance_of, counts); break;
      case 3: score_chunk<3>(rows, cols, same, chunk, table, acc, N, max_distance_of, counts); break;
      case 2: score_chunk<2>(rows, cols, same, chunk, table, acc, N, max_distance_of, counts); break;
      case 1: score_chunk<1>(rows, cols, same, chunk, table, acc, N, max_distance_of, counts); break;
      default: score_chunk<0>(rows, cols, same, chunk, table, acc, N, max_distance_of, counts); break;
    }
    chunk.first = false;
    chunk.k0 += std::max(n, 1);
    chunk.neg_sigma = neg_sigma + chunk.k0;
  } while (chunk.k0 < K);
  return counts;
}

}  // namespace attenuvis::visgraph::detail

#endif  // ATTENUVIS_X86_DISPATCH
