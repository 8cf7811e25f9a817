// The double amplitude sums of angular_sums.hpp, one clone per
// instruction set: the loop over the angles carries no value from one angle
// to the next and is vectorised.
#include "angular_sums.hpp"
#include "instruction_set_clones.hpp"

namespace attenuvis::mie::detail {

ATTENUVIS_MIE_CLONES
void angular_block_double(std::size_t first, std::size_t count, const TermOutputs<double>& t,
                          AngularArrays<double>& s) {
  angular_block(first, count, t, s);
}

}  // namespace attenuvis::mie::detail
