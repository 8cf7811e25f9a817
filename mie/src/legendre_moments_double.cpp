// The double instances of the node loops of the Legendre moments and the
// scattering-matrix expansion (attenuvis/mie/detail/legendre_moments_impl.hpp), one
// clone per instruction set with run-time choice, as the Mie term loops
// (term_block_double.cpp): an AVX2 or AVX-512 machine runs 4 or 8 nodes per
// instruction.  The kernels are inlined into each clone; with -ffp-contract=off
// (mie/CMakeLists.txt) every node sees the same IEEE operations in the same
// order on every machine, so the results are the same bits.
#include "attenuvis/mie/detail/legendre_moments_impl.hpp"
#include "instruction_set_clones.hpp"

namespace attenuvis::mie::detail {

ATTENUVIS_MIE_CLONES
void moments_chunk_double(const AmplitudeSeries<double>& c, const BonnetCoefficients<double>& k,
                          const double* two_s, const double* weight, std::size_t len, bool near, std::size_t lmax,
                          double* acc) {
  if (near)
    moments_chunk<double, true>(c, k, two_s, weight, len, lmax, acc);
  else
    moments_chunk<double, false>(c, k, two_s, weight, len, lmax, acc);
}

ATTENUVIS_MIE_CLONES
void gsf_chunk_double(const AmplitudeSeries<double>& c, const BonnetCoefficients<double>& kp,
                      const WignerCoefficients<double>& kw, const double* two_s, const double* weight,
                      std::size_t len, bool near, std::size_t lmax, double* acc) {
  if (near)
    gsf_chunk<double, true>(c, kp, kw, two_s, weight, len, lmax, acc);
  else
    gsf_chunk<double, false>(c, kp, kw, two_s, weight, len, lmax, acc);
}

}  // namespace attenuvis::mie::detail
