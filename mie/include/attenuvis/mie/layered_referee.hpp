// The 50-digit referee of the layered sphere (attenuvis/mie/layered.hpp): the
// same series (mie/src/layered_series.hpp) run in cpp_bin_float_50, in its
// own translation unit (mie/src/layered_referee.cpp).  Double input is
// converted exactly, so the referee solves the very problem layered_sphere()
// solves.  For tests and benchmarks: roughly 10 µs per series term and layer
// (~x terms), plus the start of the recurrences (~|m x| steps per layer).
#pragma once

#include <complex>
#include <vector>

#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/referee.hpp"

namespace attenuvis::mie {

// Layers as for layered_scatter(); every layer, one layer included, goes
// through the layered series (no dispatch to the homogeneous one).
Scattering<Referee> layered_scatter_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                            const Extras& extras = {}, const Options& options = {});
Efficiencies<Referee> layered_sphere_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                             const Options& options = {});
// A perfectly conducting core under shells (x: L >= 2 entries, m: L − 1).
Efficiencies<Referee> layered_sphere_referee(PerfectConductor core, const std::vector<double>& x,
                                             const std::vector<std::complex<double>>& m, const Options& options = {});

}  // namespace attenuvis::mie
