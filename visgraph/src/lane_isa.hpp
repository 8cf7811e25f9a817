// The instruction sets the lane loops are compiled for, and the vector
// square root of 16 lanes in each.  Internal to the visgraph library
// (pair_packet.cpp, visible_block.cpp).
//
// GCC keeps std::sqrt scalar (errno) unless the whole build says
// -fno-math-errno, so the vector instructions are named here, one width per
// instruction set; all are IEEE sqrt, correctly rounded like std::sqrt, so
// every width gives the same bits.  A lane loop is written once as a
// template on Isa and compiled once per instruction set by wrappers marked
// target(...) and flatten; pick_isa() chooses among them at run time.
#pragma once

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <cmath>
#include <optional>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define ATTENUVIS_X86_DISPATCH 1
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace attenuvis::visgraph::detail {

enum class Isa { baseline, avx2, avx512 };

#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target("avx512f"))) inline void sqrt16_avx512(double* d) {
  // The maskz form: GCC 12 warns that the plain form's undefined
  // pass-through operand is uninitialised.
  for (int l = 0; l < kLanes; l += 8) _mm512_store_pd(d + l, _mm512_maskz_sqrt_pd(0xFF, _mm512_load_pd(d + l)));
}
__attribute__((target("avx2"))) inline void sqrt16_avx2(double* d) {
  for (int l = 0; l < kLanes; l += 4) _mm256_store_pd(d + l, _mm256_sqrt_pd(_mm256_load_pd(d + l)));
}
#endif
inline void sqrt16_baseline(double* d) {
#if defined(__SSE2__)
  for (int l = 0; l < kLanes; l += 2) _mm_store_pd(d + l, _mm_sqrt_pd(_mm_load_pd(d + l)));
#else
  for (int l = 0; l < kLanes; ++l) d[l] = std::sqrt(d[l]);
#endif
}

// In place sqrt of 16 lanes (64-byte aligned) with the instructions of `isa`.
template <Isa isa>
inline void sqrt16(double* d) {
#ifdef ATTENUVIS_X86_DISPATCH
  if constexpr (isa == Isa::avx512) sqrt16_avx512(d);
  else if constexpr (isa == Isa::avx2) sqrt16_avx2(d);
  else sqrt16_baseline(d);
#else
  sqrt16_baseline(d);
#endif
}

// The widest instruction set this CPU runs.
inline Isa pick_isa() {
#ifdef ATTENUVIS_X86_DISPATCH
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return Isa::avx512;
  if (__builtin_cpu_supports("avx2")) return Isa::avx2;
#endif
  return Isa::baseline;
}

// The variant that the kernels' *_with functions are asked for by number
// (0: baseline x86-64 or the portable loops, 1: AVX2, 2: AVX-512F), for the
// tests that compare every variant's bits; none when this CPU lacks it (a
// build without dispatch runs the baseline only: pick_isa() says so).
inline std::optional<Isa> isa_numbered(int instruction_set) {
  const Isa isa = instruction_set == 2 ? Isa::avx512 : instruction_set == 1 ? Isa::avx2 : Isa::baseline;
  if (static_cast<int>(isa) > static_cast<int>(pick_isa())) return std::nullopt;
  return isa;
}

}  // namespace attenuvis::visgraph::detail
