// Section 4: the city (placeholder).
#include "sections.hpp"

namespace attenuvis::validation::detail {
void section_city(Context& ctx, Section& s, const SeedConditions&) {
  ctx.step("city", "checking");
  s.missing("the visibility-graph engine and city generator are not in this build.");
  s.summary.push_back("not available in this build");
}
}  // namespace attenuvis::validation::detail
