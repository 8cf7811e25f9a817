// Scoring a block of node pairs known to be in sight (a pair of leaf
// clusters that culling decided visible) without building packets: the
// |A| x |B| distances, contrast ratios and fixed-point sums are computed in
// registers, row by row against all of B at once, and each node's totals
// are added to the accumulators once per block instead of once per pair.
// Not part of the public interface: the culled pass's kernel, here for its
// test (tests/visgraph/test_visible_block.cpp).
//
// Bit-identical to scoring the same pairs through packets: the line-of-sight
// policy (coincident pairs, max_distance), the distance d =
// sqrt(dx^2 + dy^2 + dz^2) (no contraction into FMA, the squares do not
// depend on which end the difference is taken from), each pair's rounding
// to fixed point (fixed_point_exp.hpp) and integer sums, which are exact in
// any order.
#pragma once

#include <cstddef>
#include <cstdint>

namespace attenuvis::visgraph::detail {

// Nodes first .. first + count - 1 of coordinate arrays that hold them
// contiguously: a leaf (count <= 16), or as columns a run of leaves.
struct BlockSide {
  const double *x, *y, *z;
  std::size_t first;
  int count;
};

struct BlockCounts {
  std::uint64_t visible = 0, coincident = 0;
};

// Every pair (a, b), a of `rows` (at most 16), b of `cols` (any number; same:
// rows and cols are one leaf, pairs a < b only), in sight.  Credits both ends in the slot-major
// accumulators acc[s * N + node] (s = 0: degree; s = 2 + k: C for sigma k in
// units of 2^-40) and, if max_distance_of is not null (distance
// statistics), also slot 1 (distance in units of 2^-20 m) and
// max_distance_of[node], raised to the largest visible distance; slot 1 is
// left alone otherwise.  Pairs farther than max_distance are not lines of
// sight.
BlockCounts score_visible_block(const BlockSide& rows, const BlockSide& cols, bool same, const double* neg_sigma,
                                int K, double max_distance, std::int64_t* acc, std::size_t N,
                                double* max_distance_of);

// The same with the loops of one instruction set (0: baseline x86-64 or the
// portable loops, 1: AVX2, 2: AVX-512F), for the test that every variant
// gives the same bits; returns false, doing nothing, when this CPU or build
// lacks that variant.
bool score_visible_block_with(int instruction_set, const BlockSide& rows, const BlockSide& cols, bool same,
                              const double* neg_sigma, int K, double max_distance, std::int64_t* acc, std::size_t N,
                              double* max_distance_of, BlockCounts& counts);

}  // namespace attenuvis::visgraph::detail
