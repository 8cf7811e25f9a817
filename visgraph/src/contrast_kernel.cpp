// The per-pair exp is the bottleneck once rays come 16 at a time, so it is
// written as branch-free loops over the 16 lanes that the compiler turns
// into SIMD code, compiled for AVX-512, AVX2 and baseline x86-64 and picked
// at run time (GCC target_clones).  No FMA is enabled (C++ standard mode
// keeps -ffp-contract=off), so every clone computes bit-identical results.
#include "contrast_kernel.hpp"

#include <cstring>

namespace attenuvis::visgraph::detail {

namespace {
// Cody–Waite split of ln 2 (fdlibm): n * kLn2Hi is exact for |n| < 2^20.
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kLog2e = 1.44269504088896338700e+00;
// Adding 1.5 * 2^52 rounds a double of magnitude < 2^51 to the nearest
// integer, which then sits in the low mantissa bits.
constexpr double kShifter = 6755399441055744.0;
constexpr std::int64_t kShifterBits = 0x4338000000000000LL;
constexpr double kTwo52 = 4503599627370496.0;
constexpr std::int64_t kTwo52Bits = 0x4330000000000000LL;

// Round non-negative values below 2^52 to the nearest integer (ties to even).
inline void round_to_int64(const double* value, std::int64_t* out) {
  double shifted[kLanes];
  for (int l = 0; l < kLanes; ++l) shifted[l] = value[l] + kTwo52;
  std::int64_t bits[kLanes];
  std::memcpy(bits, shifted, sizeof bits);
  for (int l = 0; l < kLanes; ++l) out[l] = bits[l] - kTwo52Bits;
}
}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void contrast_lanes(const double* distance, const double* visible, const double* neg_sigma, int K,
                    std::int64_t* c_fixed, std::int64_t* d_fixed) {
  double scaled[kLanes];
  for (int l = 0; l < kLanes; ++l) scaled[l] = visible[l] * distance[l] * kDistanceScale;
  round_to_int64(scaled, d_fixed);

  for (int k = 0; k < K; ++k) {
    const double s = neg_sigma[k];
    double x[kLanes], t[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const double v = s * distance[l];
      x[l] = v < -700.0 ? -700.0 : v;
      t[l] = x[l] * kLog2e + kShifter;
    }
    std::int64_t tbits[kLanes];
    std::memcpy(tbits, t, sizeof tbits);
    double result[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const double n = t[l] - kShifter;
      const double r = (x[l] - n * kLn2Hi) - n * kLn2Lo;
      // exp(r) by Horner on the Taylor series to r^12.
      double p = 1.0 / 479001600.0;
      p = p * r + 1.0 / 39916800.0;
      p = p * r + 1.0 / 3628800.0;
      p = p * r + 1.0 / 362880.0;
      p = p * r + 1.0 / 40320.0;
      p = p * r + 1.0 / 5040.0;
      p = p * r + 1.0 / 720.0;
      p = p * r + 1.0 / 120.0;
      p = p * r + 1.0 / 24.0;
      p = p * r + 1.0 / 6.0;
      p = p * r + 0.5;
      p = p * r + 1.0;
      p = p * r + 1.0;
      // 2^n with n = tbits - kShifterBits in [-1010, 0]: a normal double.
      const std::int64_t exponent_bits = (tbits[l] - kShifterBits + 1023) << 52;
      double scale;
      std::memcpy(&scale, &exponent_bits, sizeof scale);
      result[l] = p * scale * visible[l] * kContrastScale;
    }
    round_to_int64(result, c_fixed + k * kLanes);
  }
}

}  // namespace attenuvis::visgraph::detail
