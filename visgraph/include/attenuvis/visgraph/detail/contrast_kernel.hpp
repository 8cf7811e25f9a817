// Vectorised contrast-ratio kernel: C = exp(-sigma d) for 16 lanes and K
// extinction coefficients, returned in 64-bit fixed point.  Not part of the
// public interface: the visibility pass's kernel, here for its test.
#pragma once

#include <cstdint>

namespace attenuvis::visgraph::detail {

constexpr int kLanes = 16;                       // one Embree ray packet
constexpr double kContrastScale = 1099511627776.0;  // 2^40: C in units of 2^-40
constexpr double kDistanceScale = 1048576.0;        // 2^20: distance in units of 2^-20 m

// For k < K and l < 16:
//   c_fixed[k*16 + l] = visible[l] ? round(exp(neg_sigma[k] * distance[l]) * 2^40) : 0
// and d_fixed[l] = visible[l] ? round(distance[l] * 2^20) : 0.
// `visible` holds 1.0 or 0.0.  distance must lie in [0, 4e9) m.  exp is
// evaluated to ~2 ulp (Cody–Waite reduction to |r| <= ln2/64 with a 32-entry
// table of 2^(j/32), degree-6 Taylor polynomial, truncation r^7/7! < 4e-18;
// checked against long double expl in tests/visgraph/test_contrast_kernel.cpp);
// arguments below -700 give 0 after rounding, as exp(-700)*2^40 is far below
// 1/2.  Results are bit-identical on every x86-64 CPU (no FMA contraction).
void contrast_lanes(const double* distance, const double* visible, const double* neg_sigma, int K,
                    std::int64_t* c_fixed, std::int64_t* d_fixed);

// The same with the loops of one instruction set (0: baseline x86-64 or the
// portable loops, 1: AVX2, 2: AVX-512F), for the test that every variant
// gives the same bits; returns false, doing nothing, when this CPU or build
// lacks that variant.
bool contrast_lanes_with(int instruction_set, const double* distance, const double* visible, const double* neg_sigma,
                         int K, std::int64_t* c_fixed, std::int64_t* d_fixed);

}  // namespace attenuvis::visgraph::detail
