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

}  // namespace attenuvis::weather
