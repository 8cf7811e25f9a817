// The per-pair exp is the bottleneck once rays come 16 at a time, so it is
// written as branch-free loops over the 16 lanes that the compiler turns
// into SIMD code, compiled for AVX-512, AVX2 and baseline x86-64 and picked
// at run time (GCC target_clones).  GCC contracts a*b+c into FMA by default
// in C++ (-ffp-contract=fast outside ISO C modes) wherever the target has
// FMA, which the AVX-512 clone does: contraction is switched off for this
// file so that every clone computes bit-identical results (clang's default
// contracts only within one expression, and its pragma says off as well).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <cstring>

namespace attenuvis::visgraph::detail {

namespace {
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
struct ScaledTable {
  double v[32];
};
constexpr ScaledTable scaled_table() {
  ScaledTable t{};
  for (int j = 0; j < 32; ++j) t.v[j] = kExp2Table[j] * kContrastScale;
  return t;
}
constexpr ScaledTable kExp2TableScaled = scaled_table();

// At most this many (sigma, lane) values go through one flat loop: four
// sigmas of a packet, so that the out-of-order core overlaps their
// independent polynomial chains.
constexpr int kBlock = 4 * kLanes;

// Round non-negative values below 2^52 to the nearest integer (ties to even).
inline void round_to_int64(const double* value, std::int64_t* out, int count) {
  for (int l = 0; l < count; ++l) {
    const double shifted = value[l] + kTwo52;
    std::int64_t bits;
    std::memcpy(&bits, &shifted, sizeof bits);
    out[l] = bits - kTwo52Bits;
  }
}
}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void contrast_lanes(const double* distance, const double* visible, const double* neg_sigma, int K,
                    std::int64_t* c_fixed, std::int64_t* d_fixed) {
  alignas(64) double scaled[kLanes];
  for (int l = 0; l < kLanes; ++l) scaled[l] = visible[l] * distance[l] * kDistanceScale;
  round_to_int64(scaled, d_fixed, kLanes);

  for (int k0 = 0; k0 < K; k0 += kBlock / kLanes) {
    const int m = (K - k0 < kBlock / kLanes ? K - k0 : kBlock / kLanes) * kLanes;
    alignas(64) double x[kBlock], vis[kBlock], result[kBlock];
    for (int e = 0; e < m; e += kLanes) {
      const double s = neg_sigma[k0 + e / kLanes];
      for (int l = 0; l < kLanes; ++l) {
        const double v = s * distance[l];
        x[e + l] = v < -700.0 ? -700.0 : v;
        vis[e + l] = visible[l];
      }
    }
    for (int e = 0; e < m; ++e) {
      const double t = x[e] * k32ByLn2 + kShifter;
      std::int64_t tbits;
      std::memcpy(&tbits, &t, sizeof tbits);
      const std::int64_t N = tbits - kShifterBits;  // in [-32315, 0]
      const double dn = t - kShifter;
      const double r = (x[e] - dn * kLn2By32Hi) - dn * kLn2By32Lo;
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
      result[e] = scaled_entry * p * vis[e];
    }
    round_to_int64(result, c_fixed + k0 * kLanes, m);
  }
}

}  // namespace attenuvis::visgraph::detail
