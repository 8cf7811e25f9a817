// attenuvis::weather: size distributions, refractive-index tables and files,
// ITU-R P.1817-1 weather models, OPAC aerosols, units, typed conditions and
// their grammar, sigma tables.  Typical use (what the visibility-graph app does):
//
//   auto c = attenuvis::weather::parse_condition("rain:8");   // or RainPowerLaw{8, RainLaw::seed}
//   auto s = attenuvis::weather::sigma(c, 550e-9, {});        // s.per_m, s.error_per_m, s.convention
//
#pragma once

#include "attenuvis/weather/aerosol.hpp"
#include "attenuvis/weather/aerosol_optics.hpp"
#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/coated_optics.hpp"
#include "attenuvis/weather/condition_optics.hpp"
#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/distribution_file.hpp"
#include "attenuvis/weather/domains.hpp"
#include "attenuvis/weather/empirical_models.hpp"
#include "attenuvis/weather/humidity_growth.hpp"
#include "attenuvis/weather/index_file.hpp"
#include "attenuvis/weather/opac_data.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/registry.hpp"
#include "attenuvis/weather/segmented_contour.hpp"
#include "attenuvis/weather/settings.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "attenuvis/weather/sigma_table.hpp"
#include "attenuvis/weather/size_distribution.hpp"
#include "attenuvis/weather/units.hpp"
#include "attenuvis/weather/visibility.hpp"
