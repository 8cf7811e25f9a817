// Section 5: visibility-graph performance (placeholder until visgraph_benchmark.hpp lands).
#include "sections.hpp"

namespace attenuvis::validation::detail {
void section_performance(Context& ctx, Section& s) {
  ctx.step("performance", "checking");
  s.missing("the visibility-graph benchmark API (validation/include/attenuvis/validation/visgraph_benchmark.hpp) is not in this build.");
  s.summary.push_back("not available in this build");
}
}  // namespace attenuvis::validation::detail
