// The double instances of the layered-sphere block loops (see
// layered_terms.hpp), one clone per instruction set.
#include "layered_terms.hpp"
#include "instruction_set_clones.hpp"

namespace attenuvis::mie::detail {

ATTENUVIS_MIE_CLONES
void shell_transfer_double(const ShellConstants<double>& k, const ShellInputs<double>& s, std::size_t first,
                           std::size_t count, Modes<double>& y) {
  shell_transfer(k, s, first, count, y);
}

ATTENUVIS_MIE_CLONES
void surface_terms_double(const SurfaceConstants<double>& k, const TermInputs<double>& in, const Modes<double>& y,
                          std::size_t count, TermOutputs<double>& out) {
  surface_terms(k, in, y, count, out);
}

}  // namespace attenuvis::mie::detail
