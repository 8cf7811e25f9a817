// The quadrature settings of a Mie condition's size integral on the real
// axis, one rule for sigma() (where no contour applies: rain at optical
// wavelengths) and condition_optics() (every bulk quantity).
#pragma once

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/settings.hpp"

namespace attenuvis::weather::detail {

// The tolerance and the cancel flag of `s`; for rain, beyond
// s.rain_asymptotic_x, Q_ext's large-x expansion, which gives sigma_ext
// alone (BulkOptics::scattering_computed false), and a looser resonance
// target (defined in sigma.cpp).
QuadratureSettings real_axis_settings(const MieCondition& c, const Settings& s);

}  // namespace attenuvis::weather::detail
