// Bulk optics of core–shell (coated) particles: a size distribution of core
// radii r, each core (index m_core) under a shell (index m_shell) that makes
// up the fraction f of the particle's volume, outer radius r_o = r s with
// s = (1 − f)^(−1/3).  Soot coated with sulphate or organics, a haze droplet
// grown on an insoluble core, water on ice.
//
// The integrals are those of bulk_optics.hpp over the core radius, with the
// layered-sphere efficiencies (attenuvis/mie/layered.hpp) per core cross
// section: Q(x) = Q_layered(s x) s² at the core's size parameter x = 2πr/λ
// (so σ = ∫ Q_layered π r_o² n(r) dr), g and the normalised angular
// quantities as they are.  The same adaptive Gauss–Kronrod quadrature and
// error terms, with two differences:
//   * no contour integral (contour_extinction.hpp needs the homogeneous
//     sphere's analytic continuation) and no large-x expansion of Q_ext: the
//     real axis throughout;
//   * resonance terms by the shell's index (the outer layer's ripple).
// x in the integral (and max_size_parameter) is the core's: the efficiencies
// oscillate s times faster in it than a homogeneous sphere's, which the
// adaptive rule resolves like any other structure (|K − G| per panel).
#pragma once

#include <complex>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"

namespace attenuvis::weather {

// Efficiencies of coated particles per core cross section, a panel's cores
// at a time (mie::layered_spheres; Q_back included).  Throws
// std::invalid_argument for a particle outside the layered sphere's domain.
EfficiencyBatch coated_efficiency_batch(std::complex<double> core_m, const Coating& coating);
// The same, one particle per call, plus the Legendre moments and the phase
// function `s` asks for (mie::layered_scatter).
EfficiencyFunction coated_efficiencies(std::complex<double> core_m, const Coating& coating,
                                       const QuadratureSettings& s);

// σ_ext, σ_sca, σ_abs, albedo, g and what `s` asks for, over the core radii
// `d` (two passes for angular quantities, as mie_bulk_optics).
BulkOptics coated_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> core_m,
                              const Coating& coating, const QuadratureSettings& s = {});

}  // namespace attenuvis::weather
