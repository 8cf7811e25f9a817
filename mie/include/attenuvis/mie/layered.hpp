// attenuvis::mie — Lorenz–Mie scattering by a layered sphere: a core under
// one or more concentric shells (coated soot, a haze droplet on an insoluble
// core, water on ice), or a perfectly conducting core under shells.
//
// Layer convention.  Layers are listed from the core out, l = 0 .. L−1:
//   x[l]  size parameter 2π r_l/λ of the OUTER radius of layer l (λ in the
//         medium), non-decreasing (a layer of zero thickness is allowed and
//         left out: the result is that of the sphere without it, bit for bit);
//         x[L−1] is the particle's size parameter;
//   m[l]  refractive index of layer l relative to the medium, m = n + ik,
//         k >= 0 (B&H's sign, as sphere(): attenuvis/mie.hpp).
// So a soot core of radius 0.5 µm in a sulphate shell of outer radius 1 µm at
// λ = 0.55 µm in air is x = {2π·0.5/0.55, 2π·1/0.55},
// m = {1.75+0.44i, 1.43+1e-8i}.  Efficiencies are cross sections over π r_{L−1}²,
// with the definitions of attenuvis/mie.hpp (Qback = 4|S1(π)|²/x², B&H's).
//
// The results are those of sphere()/scatter() for a layered particle: the
// Efficiencies, aₙ, bₙ and S1/S2 in a Scattering<double>, which
// scattering_matrix(x[L−1], s), phase_function_moments(s) and
// scattering_matrix_expansion(s) take as they are.  With one layer
// layered_sphere({x}, {m}) IS sphere(x, m) (the same bits).
//
// Method: Yang's (2003, Appl. Opt. 42:1710) log-derivative recursion in the
// ratio variables of the homogeneous core; the algorithm, its error analysis
// and the numerical traps of layered codes are written down in
// mie/src/layered_series.hpp.
//
// Accuracy: within 1e-10 relative (Qext, Qsca, Qback, g; floor 1e-14 Qext)
// of the same equations run with 50 digits (attenuvis/mie/referee.hpp) on the
// stress grid of tests/mie/test_layered_referee.cpp (core x 1e-4 … 1e4, shell
// 1e-3 … 10 core radii, indices 1.0001 … 10+10i, 3 and 5 layers).
// Options::precision as for sphere(): unset chooses long double recurrences
// where the referee shows double is not enough (layered_double.cpp says where).
//
// Domain (checked; std::invalid_argument names the layer and the value):
// 1 <= L <= 1000; 1e-8 <= x[0] <= x[1] <= … <= x[L−1] <= 2e5; every m[l] as
// for sphere() (0 <= n, k <= 1e6, |m| >= 0.5) with |m[l]| x[l] <= 1e7 (the
// start of the recurrences needs ~|m x| steps).
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"

namespace attenuvis::mie {

// Efficiencies of the layered sphere (x[l], m[l]), l = 0 .. L−1.
Efficiencies<double> layered_sphere(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                    const Options& options = {});

// The same, plus the coefficients and/or amplitudes asked for in `extras`.
Scattering<double> layered_scatter(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                   const Extras& extras, const Options& options = {});

// A perfectly conducting core of size parameter x[0] under shells: x has
// L >= 1 entries, m has L − 1 (m[l − 1] is the index of the shell whose outer
// size parameter is x[l]).  With no shell it is sphere(x[0], PerfectConductor).
Efficiencies<double> layered_sphere(PerfectConductor core, const std::vector<double>& x,
                                    const std::vector<std::complex<double>>& m, const Options& options = {});
Scattering<double> layered_scatter(PerfectConductor core, const std::vector<double>& x,
                                   const std::vector<std::complex<double>>& m, const Extras& extras,
                                   const Options& options = {});

// Many layered spheres (a size distribution of coated particles, a table):
// particle i has the layers offsets[i] .. offsets[i+1] − 1 of x and m, from
// the core out (offsets holds count + 1 entries).  out[i] is layered_sphere()
// of that particle, bit for bit.  As spheres() does, it never throws for bad
// input: each bad particle is reported with its index and the reason, its
// output is NaN, and every good one is computed.  The particles are shared
// out over SpheresOptions::threads threads (its instruction_set is not used:
// each call already runs its vector kernels).
std::vector<SphereError> layered_spheres(const std::size_t* offsets, const double* x, const std::complex<double>* m,
                                         std::size_t count, Efficiencies<double>* out,
                                         const SpheresOptions& options = {});

}  // namespace attenuvis::mie
