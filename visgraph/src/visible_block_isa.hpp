// The instruction-set variants of score_visible_block (visible_block.hpp)
// that live in files of their own.  Internal to the visgraph library.
#pragma once

#include "lane_isa.hpp"
#include <attenuvis/visgraph/detail/visible_block.hpp>

namespace attenuvis::visgraph::detail {

#ifdef ATTENUVIS_X86_DISPATCH
// The AVX-512 body, with intrinsics (visible_block_avx512.cpp); callable
// only where the CPU has AVX-512F.
BlockCounts score_visible_block_avx512(const BlockSide& rows, const BlockSide& cols, bool same,
                                       const double* neg_sigma, int K, double max_distance, std::int64_t* acc,
                                       std::size_t N, double* max_distance_of);
#endif

}  // namespace attenuvis::visgraph::detail
