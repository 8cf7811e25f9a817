// Properties of typed conditions (condition.hpp).
#include "attenuvis/weather/condition.hpp"

namespace attenuvis::weather {

bool needs_mie(const Condition& c) { return std::holds_alternative<MieCondition>(c); }

bool depends_on_convention(const Condition& c) {
  return std::holds_alternative<RainPowerLaw>(c) || std::holds_alternative<Snow>(c);
}

bool needs_amount(const ParametricDrops& d) {
  return !std::holds_alternative<ModifiedGammaDrops>(d.family) && !std::holds_alternative<ExponentialDrops>(d.family);
}

std::string to_string(FogPreset p) { return p == FogPreset::advection ? "advection" : "radiation"; }

std::string to_string(WaterTable t) {
  switch (t) {
    case WaterTable::hale_querry: return "hale-querry";
    case WaterTable::segelstein: return "segelstein";
    case WaterTable::ice: return "ice";
  }
  return "hale-querry";  // not reached: every enumerator is handled above
}

}  // namespace attenuvis::weather
