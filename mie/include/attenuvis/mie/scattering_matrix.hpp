// The scattering matrix of a sphere for unpolarised (or any) incident light, its
// phase function, and the per-sphere lidar quantities.
//
// Scattering matrix (B&H 4.77; the Stokes vectors of scattered and incident light
// are related by I_s = (1/(k²r²)) S I_i, k the wavenumber in the medium).  For a
// sphere only four elements are independent:
//     S11 = (|S2|² + |S1|²)/2      S12 = (|S2|² − |S1|²)/2
//     S33 = Re(S2 S1*)             S34 = Im(S2 S1*)
// with S22 = S11, S21 = S12, S44 = S33, S43 = −S34 and the other eight zero, and
// S11² = S12² + S33² + S34² at every angle (a pure Mueller matrix).  The degree of
// linear polarisation of scattered unpolarised light is −S12/S11.  Signs are
// B&H's (time dependence e^{−iωt}, m = n + ik); Mishchenko et al.'s Stokes V and
// hence their F34 have the opposite sign (see legendre_moments.hpp).
//
// Phase function.  Three normalisations are in use:
//   * p(θ) = 4π S11 / (k² Csca) = 4 S11 / (x² Qsca), with ∫ p dΩ = 4π
//     (isotropic p = 1; ½∫p dμ = 1).  This is what `phase` holds, and what
//     radiative-transfer codes (DISORT, libRadtran, Mishchenko's a1) use.
//   * p(θ)/(4π), with ∫ dΩ = 1 (units 1/sr; the "probability density" form
//     common in Monte Carlo codes and lidar work).
//   * B&H's S11 itself, unnormalised: ∫ S11 dΩ = k² Csca = π x² Qsca.
//
// Lidar (one sphere, incident light polarised or not):
//   * backscatter per steradian: Qback/(4π) = Qsca p(π)/(4π), the efficiency
//     counterpart of the backscatter coefficient β = N Cback/(4π) (1/(m sr));
//     Qback = 4|S1(π)|²/x² (B&H 4.82).
//   * lidar (extinction-to-backscatter) ratio S = Qext/(Qback/4π) = 4π Qext/Qback (sr).
//   * linear depolarisation ratio δ = (S11 − S22)/(S11 + S22) at θ = π: exactly 0
//     for every homogeneous sphere, because S22 = S11 at every angle (and at π,
//     S12 = S34 = 0, S33 = −S11 since S2(π) = −S1(π)).  A non-zero δ measured by a
//     lidar signals non-spherical particles; this model cannot produce one.
#pragma once

#include <complex>
#include <vector>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie {

// The scattering matrix at the requested angles and the phase function it gives.
struct ScatteringMatrix {
  std::vector<double> angles_deg;        // scattering angles θ (degrees), as requested
  std::vector<double> s11, s12, s33, s34;  // B&H 4.77, unnormalised
  std::vector<double> phase;             // p(θ) = 4 S11/(x² Qsca), ∫ p dΩ = 4π
};

// From the amplitudes in `s` (scatter() called with extras.angles_deg) of the
// sphere with size parameter x (the x that s was computed for: it enters the
// phase function's normalisation).  Throws std::invalid_argument if s has no
// amplitudes, x <= 0 or Qsca <= 0.
ScatteringMatrix scattering_matrix(double x, const Scattering<double>& s);

// The same, computing the amplitudes itself.
ScatteringMatrix scattering_matrix(double x, std::complex<double> m, const std::vector<double>& angles_deg);

// What a lidar sees of one sphere.
struct Lidar {
  double backscatter_per_sr = 0;       // Qback/(4π)
  double lidar_ratio_sr = 0;           // 4π Qext/Qback (infinite when Qback = 0)
  double linear_depolarisation = 0;    // always 0 for a sphere, see above
};

// The lidar quantities of a sphere from its efficiencies: Qback/4π, 4πQext/Qback
// and a linear depolarisation of 0 (S22 = S11 for every sphere).
Lidar lidar(const Efficiencies<double>& q);

}  // namespace attenuvis::mie
