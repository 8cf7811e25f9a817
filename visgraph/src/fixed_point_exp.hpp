// The contrast ratio in fixed point, one value at a time, as an inline body
// for the lane loops that score pairs (contrast_kernel.cpp: a packet's
// lanes; visible_block.cpp: a block of pairs known to be in sight).  Both
// include this one definition, so every path computes the same bits.
// Internal to the visgraph library.
//
// Files that include it must switch floating-point contraction off (see
// contrast_kernel.cpp): an FMA-capable clone would otherwise fuse the
// products, and the bits would depend on the CPU.
#pragma once

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <cstdint>
#include <cstring>

namespace attenuvis::visgraph::detail {

// exp(x) = 2^n * 2^(j/32) * exp(r),  x = (32 n + j) ln2/32 + r,  |r| <= ln2/64.
// Cody–Waite split of ln2/32: fdlibm's ln2_hi (low 32 bits zero) and ln2_lo
// divided by 32 (exact), so N * kLn2By32Hi is exact for |N| < 2^20.
constexpr double kLn2By32Hi = 6.93147180369123816490e-01 / 32;
constexpr double kLn2By32Lo = 1.90821492927058770002e-10 / 32;
constexpr double k32ByLn2 = 46.16624130844682836;  // 32 log2(e); its rounding only moves r within the bound
// Adding 1.5 * 2^52 rounds a double of magnitude < 2^51 to the nearest
// integer, which then sits in the low mantissa bits.
constexpr double kShifter = 6755399441055744.0;
constexpr std::int64_t kShifterBits = 0x4338000000000000LL;
constexpr double kTwo52 = 4503599627370496.0;
constexpr std::int64_t kTwo52Bits = 0x4330000000000000LL;
// Below this argument exp(x) * 2^40 rounds to 0 (exp(-700) * 2^40 ~ 1e-292).
constexpr double kLowestArgument = -700.0;

// 2^(j/32), j = 0..31, each rounded to nearest: computed with Python's
// decimal module at 60 digits (exp(j ln2 / 32)) and converted with float(),
// which rounds correctly.  Check: entry 16 is sqrt(2) = 0x1.6a09e667f3bcdp+0.
constexpr double kExp2Table[32] = {
    0x1.0000000000000p+0, 0x1.059b0d3158574p+0, 0x1.0b5586cf9890fp+0, 0x1.11301d0125b51p+0,
    0x1.172b83c7d517bp+0, 0x1.1d4873168b9aap+0, 0x1.2387a6e756238p+0, 0x1.29e9df51fdee1p+0,
    0x1.306fe0a31b715p+0, 0x1.371a7373aa9cbp+0, 0x1.3dea64c123422p+0, 0x1.44e086061892dp+0,
    0x1.4bfdad5362a27p+0, 0x1.5342b569d4f82p+0, 0x1.5ab07dd485429p+0, 0x1.6247eb03a5585p+0,
    0x1.6a09e667f3bcdp+0, 0x1.71f75e8ec5f74p+0, 0x1.7a11473eb0187p+0, 0x1.82589994cce13p+0,
    0x1.8ace5422aa0dbp+0, 0x1.93737b0cdc5e5p+0, 0x1.9c49182a3f090p+0, 0x1.a5503b23e255dp+0,
    0x1.ae89f995ad3adp+0, 0x1.b7f76f2fb5e47p+0, 0x1.c199bdd85529cp+0, 0x1.cb720dcef9069p+0,
    0x1.d5818dcfba487p+0, 0x1.dfc97337b9b5fp+0, 0x1.ea4afa2a490dap+0, 0x1.f50765b6e4540p+0};

// The table times 2^40 (exact: a power of two), saving one multiplication per value.
struct ScaledExp2Table {
  double v[32];
};
constexpr ScaledExp2Table scaled_exp2_table() {
  ScaledExp2Table t{};
  for (int j = 0; j < 32; ++j) t.v[j] = kExp2Table[j] * kContrastScale;
  return t;
}
inline constexpr ScaledExp2Table kExp2TableScaled = scaled_exp2_table();

// exp(x) * 2^40 for x in [-700, 0] (callers clamp), to ~2 ulp: the value
// that is then rounded to an integer (round_fixed).  Branch-free, so that
// loops over lanes calling it vectorise.
inline double scaled_exp(double x) {
  const double t = x * k32ByLn2 + kShifter;
  std::int64_t tbits;
  std::memcpy(&tbits, &t, sizeof tbits);
  const std::int64_t N = tbits - kShifterBits;  // in [-32315, 0]
  const double dn = t - kShifter;
  const double r = (x - dn * kLn2By32Hi) - dn * kLn2By32Lo;
  // exp(r) by Horner on the Taylor series to r^6: truncation
  // r^7/7! < 4e-18 for |r| <= ln2/64.
  double p = 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^(j/32) 2^40 2^n, n = floor(N / 32) in [-1010, 0], by adding n to
  // the table entry's exponent field: exact, the result (>= 2^-970)
  // being a normal double.
  const double entry = kExp2TableScaled.v[N & 31];
  std::int64_t entry_bits;
  std::memcpy(&entry_bits, &entry, sizeof entry_bits);
  entry_bits += (N >> 5) * (std::int64_t{1} << 52);
  double scaled_entry;
  std::memcpy(&scaled_entry, &entry_bits, sizeof scaled_entry);
  return scaled_entry * p;
}

// A non-negative value below 2^52 rounded to the nearest integer (ties to
// even), by adding 2^52 and reading the low mantissa bits.
inline std::int64_t round_fixed(double value) {
  const double shifted = value + kTwo52;
  std::int64_t bits;
  std::memcpy(&bits, &shifted, sizeof bits);
  return bits - kTwo52Bits;
}

}  // namespace attenuvis::visgraph::detail
