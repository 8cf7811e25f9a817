// Private to the reproduction job: the scenes of the seed paper (Sec. Case
// Study Models) shown in 3D, and the one place that says which city the
// report generates (the scenes and the city sections both build it).
#pragma once

#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/obj.hpp>

#include "sections.hpp"

namespace attenuvis::validation::detail {

// The report's city: make_city's documented defaults (seed 2021, 61 blocks);
// quick mode keeps only the central block and its first ring.
visgraph::CityOptions report_city_options(bool quick);

// 3D views of the five classic layouts and of the city (seed Figs. vg_cases
// and vg_case_city), drawn from OBJ files written beside the report.
void section_scenes(Context& ctx, Section& s);

}  // namespace attenuvis::validation::detail
