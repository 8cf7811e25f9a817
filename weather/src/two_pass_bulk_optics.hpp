// The bulk integrals with angular quantities in a second pass
// (bulk_optics.hpp: mie_bulk_optics) and the angular terms of one particle,
// for any particle: the homogeneous sphere's (mie_bulk_optics.cpp, which
// defines both) and the coated one's (coated_optics.cpp).
// Private to the weather library.
#pragma once

#include <complex>
#include <functional>

#include "attenuvis/mie.hpp"
#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather::detail {

// `cheap`: the efficiencies without angular terms (pass A); `angular(s)`: the
// efficiencies with the angular terms `s` asks for (pass B).  m: the index
// the error terms go by (resonances).
BulkOptics two_pass_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                                const EfficiencyBatch& cheap,
                                const std::function<EfficiencyFunction(const QuadratureSettings&)>& angular,
                                const QuadratureSettings& s);

// The angular terms of one particle into e, from its Scattering (with the
// coefficients when L >= 0, the amplitudes at the phase function's angles):
// chi_0..chi_L, p(theta) (x: the size parameter the amplitudes refer to), and
// with `polarised` alpha1..beta2, each padded to L + 1 with the exact zeros
// above 2N.
void add_angular_terms(const mie::Scattering<double>& sc, double x, int L, bool polarised, Efficiency& e);

}  // namespace attenuvis::weather::detail
