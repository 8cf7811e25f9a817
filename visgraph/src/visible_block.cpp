// Blocks of pairs in sight, scored without packets (visible_block.hpp).
//
// Compiled like the packet kernels (contrast_kernel.cpp, pair_packet.cpp):
// no floating-point contraction, so every instruction set rounds the same
// way, and one copy of the loops per instruction set (lane_isa.hpp).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include <attenuvis/visgraph/detail/visible_block.hpp>

#include "fixed_point_exp.hpp"
#include "lane_isa.hpp"
#include "visible_block_isa.hpp"
#include "pair_packet.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <vector>

namespace attenuvis::visgraph::detail {

namespace {
// (sigma, lane) values per flat loop: four sigmas, so that the out-of-order
// core overlaps their independent polynomial chains (as contrast_lanes).
constexpr int kFlat = 4 * kLanes;

// One row against the (padded) columns.  mask[l] = 1.0 for the columns that
// pair with this row.
struct RowAgainstColumns {
  double ox, oy, oz;
  const double *bx, *by, *bz, *mask;
};

// Running totals of a block: per column and slot col[s * kLanes + l],
// largest distance per column as the bits of a non-negative double (which
// order like the doubles, and reduce as integers: vectorised), counts.
struct BlockTotals {
  std::int64_t* col;
  bool distances;  // distance sums and maxima (distance statistics)
  std::int64_t col_max_bits[kLanes];
  std::int64_t visible = 0, coincident = 0;
};

inline std::int64_t bits_of(double v) {
  std::int64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
inline double double_of(std::int64_t b) {
  double v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

// Scores one row: its totals per slot into row_total[s], its largest
// distance (as bits) into row_max_bits.  Every loop is over the 16 lanes or
// a flat block of them, without control flow and with integer reductions
// only, so that each one vectorises.
template <Isa isa>
inline void score_row(const RowAgainstColumns& r, const double* neg_sigma, int K, double max_distance,
                      std::int64_t* row_total, std::int64_t& row_max_bits, BlockTotals& t) {
  alignas(64) double d[kLanes], vis[kLanes], dist[kLanes];
  alignas(64) std::int64_t vis_int[kLanes], coincident[kLanes], fixed[kFlat];
  for (int l = 0; l < kLanes; ++l) {
    const double dx = r.bx[l] - r.ox, dy = r.by[l] - r.oy, dz = r.bz[l] - r.oz;
    d[l] = dx * dx + dy * dy + dz * dz;
  }
  sqrt16<isa>(d);
  // The policy of build_packet: coincident pairs are neither visible nor
  // counted; a candidate in sight scores its distance.
  for (int l = 0; l < kLanes; ++l) {
    const bool act = r.mask[l] != 0.0;
    const bool apart = d[l] >= kCoincident;
    const bool candidate = act & apart & (d[l] <= max_distance);
    vis[l] = candidate ? 1.0 : 0.0;
    dist[l] = candidate ? d[l] : 0.0;
    vis_int[l] = candidate ? 1 : 0;
    coincident[l] = (act & !apart) ? 1 : 0;
  }
  std::int64_t degree = 0, far = 0;
  for (int l = 0; l < kLanes; ++l) {
    degree += vis_int[l];
    t.coincident += coincident[l];
    t.col[l] += vis_int[l];
    const std::int64_t b = bits_of(dist[l]);
    far = far > b ? far : b;
    t.col_max_bits[l] = t.col_max_bits[l] > b ? t.col_max_bits[l] : b;
  }
  t.visible += degree;
  row_total[0] += degree;
  row_max_bits = row_max_bits > far ? row_max_bits : far;
  alignas(64) double value[kFlat], x[kFlat], vis_flat[kFlat];
  if (t.distances) {
    for (int l = 0; l < kLanes; ++l) value[l] = vis[l] * dist[l] * kDistanceScale;
    std::int64_t distance_sum = 0;
    for (int l = 0; l < kLanes; ++l) {
      const std::int64_t f = round_fixed(value[l]);
      distance_sum += f;
      t.col[kLanes + l] += f;
    }
    row_total[1] += distance_sum;
  }
  for (int k0 = 0; k0 < K; k0 += kFlat / kLanes) {
    const int m = (K - k0 < kFlat / kLanes ? K - k0 : kFlat / kLanes) * kLanes;
    for (int e = 0; e < m; e += kLanes) {
      const double s = neg_sigma[k0 + e / kLanes];
      for (int l = 0; l < kLanes; ++l) {
        const double v = s * dist[l];
        x[e + l] = v < kLowestArgument ? kLowestArgument : v;
        vis_flat[e + l] = vis[l];
      }
    }
    for (int e = 0; e < m; ++e) value[e] = scaled_exp(x[e]) * vis_flat[e];
    for (int e = 0; e < m; ++e) fixed[e] = round_fixed(value[e]);
    std::int64_t* col = t.col + static_cast<std::ptrdiff_t>(2 + k0) * kLanes;
    for (int e = 0; e < m; ++e) col[e] += fixed[e];
    for (int e = 0; e < m; e += kLanes) {
      std::int64_t sum = 0;
      for (int l = 0; l < kLanes; ++l) sum += fixed[e + l];
      row_total[2 + k0 + e / kLanes] += sum;
    }
  }
}

// Rows against at most 16 columns.
template <Isa isa>
inline BlockCounts score_block_lanes(const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma,
                                     int K, double max_distance, std::int64_t* acc, std::size_t N,
                                     double* max_distance_of) {
  alignas(64) double bx[kLanes], by[kLanes], bz[kLanes], col_mask[kLanes], mask[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const bool real = l < cols.count;
    const std::size_t j = cols.first + static_cast<std::size_t>(real ? l : 0);
    bx[l] = real ? cols.x[j] : 0.0;
    by[l] = real ? cols.y[j] : 0.0;
    bz[l] = real ? cols.z[j] : 0.0;
    col_mask[l] = real ? 1.0 : 0.0;
  }
  // Column totals per slot, lane by lane; row totals one row at a time.
  const std::size_t slots = 2 + static_cast<std::size_t>(K);
  constexpr std::size_t kStackSlots = 2 + 8;
  alignas(64) std::int64_t col_stack[kStackSlots * kLanes];
  std::int64_t row_stack[kStackSlots];
  std::vector<std::int64_t> heap(slots > kStackSlots ? slots * (kLanes + 1) : 0);
  BlockTotals t;
  t.distances = max_distance_of != nullptr;
  t.col = slots > kStackSlots ? heap.data() : col_stack;
  std::int64_t* row_total = slots > kStackSlots ? heap.data() + slots * kLanes : row_stack;
  for (std::size_t e = 0; e < slots * kLanes; ++e) t.col[e] = 0;
  for (int l = 0; l < kLanes; ++l) t.col_max_bits[l] = 0;
  for (int a = 0; a < rows.count; ++a) {
    const std::size_t i = rows.first + static_cast<std::size_t>(a);
    for (int l = 0; l < kLanes; ++l) mask[l] = (!same || l > a) ? col_mask[l] : 0.0;
    for (std::size_t s = 0; s < slots; ++s) row_total[s] = 0;
    std::int64_t row_max_bits = 0;
    const RowAgainstColumns r{rows.x[i], rows.y[i], rows.z[i], bx, by, bz, mask};
    score_row<isa>(r, neg_sigma, K, max_distance, row_total, row_max_bits, t);
    for (std::size_t s = 0; s < slots; ++s) acc[s * N + i] += row_total[s];
    if (max_distance_of) max_distance_of[i] = std::max(max_distance_of[i], double_of(row_max_bits));
  }
  for (int l = 0; l < cols.count; ++l) {
    const std::size_t j = cols.first + static_cast<std::size_t>(l);
    for (std::size_t s = 0; s < slots; ++s) acc[s * N + j] += t.col[s * kLanes + static_cast<std::size_t>(l)];
    if (max_distance_of) max_distance_of[j] = std::max(max_distance_of[j], double_of(t.col_max_bits[l]));
  }
  return BlockCounts{static_cast<std::uint64_t>(t.visible), static_cast<std::uint64_t>(t.coincident)};
}

// Rows against any number of columns, 16 at a time.
template <Isa isa>
inline BlockCounts score_run_lanes(const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma,
                                   int K, double max_distance, std::int64_t* acc, std::size_t N,
                                   double* max_distance_of) {
  if (same) return score_block_lanes<isa>(rows, cols, true, neg_sigma, K, max_distance, acc, N, max_distance_of);
  BlockCounts total;
  for (int c0 = 0; c0 < cols.count; c0 += kLanes) {
    const BlockSide part{cols.x, cols.y, cols.z, cols.first + static_cast<std::size_t>(c0), std::min(kLanes, cols.count - c0)};
    const BlockCounts counts =
        score_block_lanes<isa>(rows, part, false, neg_sigma, K, max_distance, acc, N, max_distance_of);
    total.visible += counts.visible;
    total.coincident += counts.coincident;
  }
  return total;
}

using BlockFunction = BlockCounts (*)(const BlockSide&, const BlockSide&, bool, const double*, int, double,
                                      std::int64_t*, std::size_t, double*);
#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target("avx2"), flatten)) BlockCounts score_block_avx2(
    const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma, int K, double max_distance,
    std::int64_t* acc, std::size_t N, double* max_distance_of) {
  return score_run_lanes<Isa::avx2>(rows, cols, same, neg_sigma, K, max_distance, acc, N, max_distance_of);
}
#endif
__attribute__((flatten)) BlockCounts score_block_baseline(const BlockSide& rows, const BlockSide& cols, bool same,
                                                         const double* neg_sigma, int K, double max_distance,
                                                         std::int64_t* acc, std::size_t N, double* max_distance_of) {
  return score_run_lanes<Isa::baseline>(rows, cols, same, neg_sigma, K, max_distance, acc, N, max_distance_of);
}

BlockFunction block_function(Isa isa) {
#ifdef ATTENUVIS_X86_DISPATCH
  if (isa == Isa::avx512) return score_visible_block_avx512;
  if (isa == Isa::avx2) return score_block_avx2;
#endif
  (void)isa;
  return score_block_baseline;
}
}  // namespace

bool score_visible_block_with(int instruction_set, const BlockSide& rows, const BlockSide& cols, bool same,
                              const double* neg_sigma, int K, double max_distance, std::int64_t* acc, std::size_t N,
                              double* max_distance_of, BlockCounts& counts) {
  const std::optional<Isa> isa = isa_numbered(instruction_set);
  if (!isa) return false;
  counts = block_function(*isa)(rows, cols, same, neg_sigma, K, max_distance, acc, N, max_distance_of);
  return true;
}

BlockCounts score_visible_block(const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma,
                                int K, double max_distance, std::int64_t* acc, std::size_t N,
                                double* max_distance_of) {
  static const BlockFunction chosen = block_function(pick_isa());
  return chosen(rows, cols, same, neg_sigma, K, max_distance, acc, N, max_distance_of);
}

}  // namespace attenuvis::visgraph::detail
