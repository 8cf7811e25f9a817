// The double instances of the per-block Mie term loops (see
// attenuvis/mie/term_block.hpp), one clone per instruction set.
#include "attenuvis/mie/term_block.hpp"

namespace attenuvis::mie::detail {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define ATTENUVIS_MIE_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ATTENUVIS_MIE_CLONES
#endif

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

}  // namespace attenuvis::mie::detail
