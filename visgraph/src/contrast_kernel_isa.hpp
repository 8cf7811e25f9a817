// The instruction-set variant of contrast_lanes (contrast_kernel.hpp) that
// lives in a file of its own.  Internal to the visgraph library.
#pragma once

#include "lane_isa.hpp"

#include <cstdint>

namespace attenuvis::visgraph::detail {

#ifdef ATTENUVIS_X86_DISPATCH
// The AVX-512 body, with intrinsics (contrast_kernel_avx512.cpp); callable
// only where the CPU has AVX-512F.
void contrast_lanes_avx512(const double* distance, const double* visible, const double* neg_sigma, int K,
                           std::int64_t* c_fixed, std::int64_t* d_fixed);
#endif

}  // namespace attenuvis::visgraph::detail
