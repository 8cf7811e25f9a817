// Section 3: the seed's five layouts (placeholder).
#include "sections.hpp"

namespace attenuvis::validation::detail {
void section_layouts(Context& ctx, Section& s, const SeedConditions&) {
  ctx.step("layouts", "checking");
  s.missing("the visibility-graph engine and scene generators are not in this build.");
  s.summary.push_back("not available in this build");
}
}  // namespace attenuvis::validation::detail
