// Section 1: Mie validation (placeholder until mie_accuracy.hpp lands).
#include "sections.hpp"

namespace attenuvis::validation::detail {
void section_mie(Context& ctx, Section& s) {
  ctx.step("mie", "checking");
  s.missing("the Mie accuracy API (validation/include/attenuvis/validation/mie_accuracy.hpp) is not in this build.");
  s.summary.push_back("not available in this build");
}
}  // namespace attenuvis::validation::detail
