// The double instances of the per-block Mie term loops (see
// term_block.hpp), one clone per instruction set.
#include "term_block.hpp"
#include "instruction_set_clones.hpp"

#include <algorithm>
#include <cmath>

namespace attenuvis::mie::detail {

ATTENUVIS_MIE_CLONES
void sphere_terms_double(const TermConstants<double>& k, const TermInputs<double>& in, std::size_t count,
                         TermOutputs<double>& out) {
  sphere_terms(k, in, count, out);
}

ATTENUVIS_MIE_CLONES
void conductor_terms_double(const TermConstants<double>& k, const TermInputs<double>& in, std::size_t count,
                            TermOutputs<double>& out) {
  conductor_terms(k, in, count, out);
}

ATTENUVIS_MIE_CLONES
void sum_terms_double(const TermInputs<double>& in, std::size_t count, const Complex<double>& a_prev,
                      const Complex<double>& b_prev, TermOutputs<double>& out) {
  sum_terms(in, count, a_prev, b_prev, out);
}

ATTENUVIS_MIE_CLONES
std::size_t sum_block_double(const TermOutputs<double>& t, std::size_t first, std::size_t count, double x,
                             double tol, bool converged_rule, VectorSums& s) {
  // Two vectors of four (one register each with AVX2): lanes 0–3 and 4–7.
  typedef double V __attribute__((vector_size(32)));
  constexpr int kWidth = 4;
  // The terms of an order are gathered in SumLane's order.
  static_assert(SumLane::ext == 0 && SumLane::sca == 1 && SumLane::abs == 2 && SumLane::back_re == 3 &&
                    SumLane::back_im == 4 && SumLane::g_cross == 5 && SumLane::g_self == 6 && SumLane::count < 8,
                "the vectors v0, v1 below list the terms by SumLane");
  V sum0, sum1, carry0, carry1;
  __builtin_memcpy(&sum0, s.sum, sizeof sum0);
  __builtin_memcpy(&sum1, s.sum + kWidth, sizeof sum1);
  __builtin_memcpy(&carry0, s.carry, sizeof carry0);
  __builtin_memcpy(&carry1, s.carry + kWidth, sizeof carry1);
  // The running sum of lane c.
  const auto running = [&](int c) { return c < kWidth ? sum0[c] : sum1[c - kWidth]; };
  std::size_t i = 0;
  while (i < count) {
    const std::size_t n = first + i;
    // g_cross starts at n = 2 (SeriesSums::add); its n = 1 entry is not added.
    const V v0 = {t.ext[i], t.sca[i], t.abs[i], t.back_re[i]};
    const V v1 = {t.back_im[i], n >= 2 ? t.g_cross[i] : 0.0, t.g_self[i], 0.0};
    const V y0 = v0 - carry0, y1 = v1 - carry1;  // KahanSum::add, lane by lane
    const V u0 = sum0 + y0, u1 = sum1 + y1;
    carry0 = (u0 - sum0) - y0, carry1 = (u1 - sum1) - y1;
    sum0 = u0, sum1 = u1;
    ++i;
    if (converged_rule && series_converged(n, x, t.size[i - 1], tol, running(SumLane::ext),
                                           running(SumLane::back_re), running(SumLane::back_im))) {
      s.converged = true;
      break;
    }
  }
  __builtin_memcpy(s.sum, &sum0, sizeof sum0);
  __builtin_memcpy(s.sum + kWidth, &sum1, sizeof sum1);
  __builtin_memcpy(s.carry, &carry0, sizeof carry0);
  __builtin_memcpy(s.carry + kWidth, &carry1, sizeof carry1);
  return i;
}

}  // namespace attenuvis::mie::detail
