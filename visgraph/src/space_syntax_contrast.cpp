// Contrast ratios of a row of lines, exp(-sigma d), vectorised
// (space_syntax_measures.hpp).  The weighted measures evaluate one per line
// end and weather: std::exp is a library call that no loop vectorises, and
// was most of their time.
//
// x = -sigma d <= 0 is reduced as x = k ln2 + r with k = round(x / ln2),
// ln2 split in a high part with 21 trailing zero bits (so k ln2_hi is exact
// for |k| < 2^21) and a low part (Cody & Waite 1980), |r| <= ln2/2; exp(r)
// by its Taylor polynomial of degree 13 in Horner form, whose truncation
// (ln2/2)^14/14! < 4e-18 is far below an ulp; the result is scaled by 2^k
// through the exponent bits.  Rounding: about 1 ulp.  Arguments below -708
// (results near or below the smallest normal double) go to std::exp.  The
// files are compiled without contraction, so every instruction set gives
// the same bits.
#include "space_syntax_measures.hpp"

#include <cmath>
#include <cstring>

namespace attenuvis::visgraph::space_syntax_detail {

namespace {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ATTENUVIS_EXP_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_EXP_CLONES
#endif

constexpr double kLog2e = 1.4426950408889634074;
constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 0x3fe62e42fee00000
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kShifter = 6755399441055744.0;          // 1.5 x 2^52: rounds to an integer in the low bits
constexpr double kSmallest = -708.0;

ATTENUVIS_EXP_CLONES void contrasts_lanes(double sigma, const double* d, double* c, std::size_t n) {
  for (std::size_t t = 0; t < n; ++t) {
    const double x0 = -sigma * d[t];
    const double x = x0 < kSmallest ? kSmallest : x0;
    const double shifted = x * kLog2e + kShifter;
    const double k = shifted - kShifter;
    const double r = (x - k * kLn2Hi) - k * kLn2Lo;
    double p = 1.0 / 6227020800.0;  // 1/13!
    p = p * r + 1.0 / 479001600.0;
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
    std::int64_t bits;
    std::memcpy(&bits, &shifted, sizeof bits);
    // The low bits of `shifted` hold k (two's complement, |k| <= 1022).
    const std::int64_t e = ((bits & 0xfffff) ^ 0x80000) - 0x80000;
    const std::int64_t scale_bits = (e + 1023) << 52;
    double scale;
    std::memcpy(&scale, &scale_bits, sizeof scale);
    c[t] = p * scale;
  }
}
}  // namespace

void contrasts(double sigma, const double* d, double* c, std::size_t n) {
  contrasts_lanes(sigma, d, c, n);
  for (std::size_t t = 0; t < n; ++t)
    if (-sigma * d[t] < kSmallest) c[t] = std::exp(-sigma * d[t]);
}

}  // namespace attenuvis::visgraph::space_syntax_detail
