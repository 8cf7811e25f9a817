// The bulk integrals with angular quantities in a second pass
// (bulk_optics.hpp: mie_bulk_optics), for any particle: the homogeneous
// sphere's (mie_bulk_optics.cpp) and the coated one's (coated_optics.cpp).
// Private to the weather library.
#pragma once

#include <complex>
#include <functional>

#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather::detail {

// `cheap`: the efficiencies without angular terms (pass A); `angular(s)`: the
// efficiencies with the angular terms `s` asks for (pass B).  m: the index
// the error terms go by (resonances).
BulkOptics two_pass_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                                const EfficiencyBatch& cheap,
                                const std::function<EfficiencyFunction(const QuadratureSettings&)>& angular,
                                const QuadratureSettings& s);

}  // namespace attenuvis::weather::detail
