// The double amplitude sums of attenuvis/mie/angular_sums.hpp, one clone per
// instruction set: the loop over the angles carries no value from one angle
// to the next and is vectorised (ivdep: the arrays are distinct, which GCC
// cannot prove through the vectors' pointers).
#include "attenuvis/mie/angular_sums.hpp"
#include "instruction_set_clones.hpp"

namespace attenuvis::mie::detail {

ATTENUVIS_MIE_CLONES
void angular_block_double(std::size_t first, std::size_t count, const TermOutputs<double>& t, AngularArrays& s) {
  const std::size_t na = s.mu.size();
  const double* mu = s.mu.data();
  double* pi_prev = s.pi_prev.data();
  double* pi_cur = s.pi_cur.data();
  double* s1r = s.s1_re.data();
  double* s1i = s.s1_im.data();
  double* s2r = s.s2_re.data();
  double* s2i = s.s2_im.data();
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t n = first + i;
    const double rn = double(n), rn1 = rn + 1, f = double(2 * n + 1) / (rn * rn1);
    const double far = t.a_re[i] * f, fai = t.a_im[i] * f, fbr = t.b_re[i] * f, fbi = t.b_im[i] * f;
    // π₀ = 0, π₁ = 1 are the initial arrays; from n = 2 on, πₙ by its recurrence.
    const bool recur = n >= 2;
    const double w = double(2 * n - 1), d = recur ? double(n - 1) : 1.0;
#pragma GCC ivdep
    for (std::size_t j = 0; j < na; ++j) {
      double pi_n = pi_cur[j], prev = pi_prev[j];
      if (recur) {
        prev = pi_n;
        pi_n = (w * mu[j] * pi_cur[j] - rn * pi_prev[j]) / d;
        pi_prev[j] = prev;
        pi_cur[j] = pi_n;
      }
      const double tau = rn * mu[j] * pi_n - rn1 * prev;
      s1r[j] += far * pi_n + fbr * tau;
      s1i[j] += fai * pi_n + fbi * tau;
      s2r[j] += far * tau + fbr * pi_n;
      s2i[j] += fai * tau + fbi * pi_n;
    }
  }
}

}  // namespace attenuvis::mie::detail
