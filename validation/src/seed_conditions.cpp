// The seed paper's five weather conditions and the σ values the visibility
// sections run with.
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sections.hpp"

namespace attenuvis::validation::detail {

namespace {
// Mie over a fog preset, water index from the settings (Hale & Querry by default).
weather::Condition fog(weather::FogPreset preset) {
  return weather::MieCondition{preset, weather::SettingsWaterTable{}, weather::AsGiven{}, std::nullopt};
}
}  // namespace

SeedConditions seed_published_conditions() {
  // Published σ of Schwartz, Vinnikov & Federici (SimAUD 2021); each with the
  // place in the paper where it is printed.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SeedConditions c;
  c.rows = {
      {"clear", "clear", weather::ClearAir{}, 0.00015, "seed paper, Sec. Results / Visibility Graph Case (clear weather sigma = 0.00015)",
       nan, nan, nan, nan, ""},
      {"rain 8 mm/h", "rain:8", weather::RainPowerLaw{8.0, weather::RainLaw::seed}, 0.0045, "seed paper, Sec. Results, text of Fig. vg_weather (rain sigma = 0.0045)", nan,
       nan, nan, nan, ""},
      {"heavy advection fog", "fog:advection", fog(weather::FogPreset::advection), 0.02874311,
       "seed paper, Sec. Methodology / Fog (sigma = 0.02874311 m^-1 at 550 nm)", nan, nan, nan, nan, ""},
      {"moderate radiation fog", "fog:radiation", fog(weather::FogPreset::radiation), 0.00863808,
       "seed paper, Sec. Methodology / Fog (sigma = 0.00863808 m^-1 at 550 nm)", nan, nan, nan, nan, ""},
      {"dry snow 4 mm/h", "snow:dry:4", weather::Snow{weather::SnowType::dry, 4.0}, 0.0374, "seed paper, Sec. Results, text of Fig. vg_weather (snow sigma = 0.0374)",
       nan, nan, nan, nan, ""},
  };
  return c;
}

namespace {
std::string tag_of(const std::string& condition) {
  std::string t;
  for (char ch : condition)
    if (std::isalnum(static_cast<unsigned char>(ch))) t += ch;
  return t;
}
}  // namespace

std::vector<VgCondition> vg_conditions(const SeedConditions& seed, const std::string& condition) {
  const SeedConditions::Row* row = seed.find(condition);
  if (!row) throw std::logic_error("vg_conditions: no seed condition '" + condition + "'");
  const std::string tag = tag_of(condition);
  const std::string brief = condition == "clear" ? "clear"
                            : condition == "rain:8" ? "rain 8"
                            : condition == "fog:advection" ? "fog HA"
                            : condition == "fog:radiation" ? "fog MR"
                            : condition == "snow:dry:4" ? "dry snow 4"
                                                          : condition;
  if (!std::isfinite(row->itu) || !std::isfinite(row->seed))
    throw std::logic_error("vg_conditions: sigma of '" + condition + "' not computed yet (weather section)");
  if (row->itu == row->seed) return {{row->name, tag, brief, condition, "both", row->itu}};
  return {{row->name + " (itu convention)", tag + "_itu", brief + ", itu", condition, "itu", row->itu},
          {row->name + " (seed convention)", tag + "_seed", brief + ", seed", condition, "seed", row->seed}};
}

}  // namespace attenuvis::validation::detail
