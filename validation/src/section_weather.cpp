// Section 2: distributions and weather (placeholder).
#include "sections.hpp"

namespace attenuvis::validation::detail {
void section_weather(Context& ctx, Section& s, SeedConditions& seed) {
  ctx.step("weather", "checking");
  seed.available = false;
  seed.why_missing = "weather API not in this build";
  s.missing("the weather API (weather/include/attenuvis/weather.hpp) is not in this build.");
  s.summary.push_back("not available in this build");
}
}  // namespace attenuvis::validation::detail
