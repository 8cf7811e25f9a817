// Bulk optical properties of a size distribution: the integrals
//
//   sigma_ext = int Q_ext(x) pi r^2 n(r) dr,   x = 2 pi r / lambda      (van de Hulst 1957, Sec. 4.22)
//   sigma_sca, sigma_abs likewise;  albedo = sigma_sca / sigma_ext;
//   g = int g(x) Q_sca(x) pi r^2 n(r) dr / sigma_sca,
//
// computed with Gauss-Kronrod rules from Boost.Math (boost/math/quadrature/
// gauss_kronrod.hpp) in u = ln r, refined adaptively (globally, worst panel
// first, QUADPACK QAG-style) until the summed |Kronrod - Gauss| of every panel
// is below rel_tolerance x sigma_ext.  One efficiency evaluation serves all four
// integrands.
//
// The reported error of each integral is the sum of
//   quadrature  sum over panels of |K - G| (an overestimate for smooth integrands),
//   tails       q_bound x pi x (exact 2nd moment outside the integration range);
//               the range holds all but tail_fraction of that moment,
//   asymptotic  where x > asymptotic_x, Q_ext is replaced by its large-sphere
//               expansion and |Q_ext - expansion| <= its stated bound is integrated,
//   aliasing    on panels wider than the rule resolves (0.6 x points in x),
//               1.5 x (sampled range of Q) x (panel's geometric cross-section)
//               is added, since K and G can alias alike there,
//   resonance   for nearly non-absorbing particles, what panels at the
//               resonance floor still disagree on (resonance.hpp); reported,
//               not counted against the tolerance.
// If the quadrature part cannot be brought below the tolerance within
// max_evaluations, or a moment diverges, the function throws
// std::runtime_error naming the integral and the reason.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <string>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// Efficiencies of one sphere at size parameter x (what mie::sphere returns).
struct Efficiency {
  double qext = 0, qsca = 0, qabs = 0, g = 0;
};
using EfficiencyFunction = std::function<Efficiency(double x)>;

struct QuadratureSettings {
  double rel_tolerance = 1e-9;     // on every integral, relative to sigma_ext
  int kronrod_points = 31;         // Boost.Math gauss_kronrod order: 15, 21, 31, 41, 51 or 61
  double tail_fraction = 0;        // fraction of the r^2 moment left outside; 0: 1e-3 * rel_tolerance
  std::size_t max_evaluations = 400000;
  double asymptotic_x = 0;         // > 0: use the large-x expansion of Q_ext beyond this x (extinction only)
  bool estimate_resonances = true; // Im(m) < resonance_free_k(): stop splitting at resonance_x_span
  double resonance_x_span = 0.1;   // narrowest panel (in x) for nearly non-absorbing spheres (see resonance.hpp)
};

struct IntegralEstimate {
  double value = 0;
  double quadrature_error = 0, tail_error = 0, asymptotic_error = 0, resonance_error = 0;
  double error() const { return quadrature_error + tail_error + asymptotic_error + resonance_error; }
};

struct BulkOptics {
  IntegralEstimate extinction, scattering, absorption;  // 1/m
  double albedo = 0, albedo_error = 0;
  double asymmetry = 0, asymmetry_error = 0;
  std::size_t evaluations = 0;
  std::size_t floor_panels = 0;     // panels left at resonance_x_span
  double max_size_parameter = 0;
  bool scattering_computed = true;  // false when the asymptotic region (extinction only) was used
  std::string method;               // rule, tolerance, tail cut, in words
};

// With any efficiency function (analytic test integrands, a cached Mie table...).
// `m` is used only for the error terms (resonances, large-x bound); the default
// (Im m = 1) switches the resonance term off, as for a smooth test integrand.
BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyFunction& q,
                                 const QuadratureSettings& s = {}, std::complex<double> m = {1.33, 1.0});

// With Lorenz-Mie efficiencies (attenuvis::mie::sphere) of a homogeneous sphere
// of relative refractive index m = n + i k.
BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s = {});


}  // namespace attenuvis::weather
