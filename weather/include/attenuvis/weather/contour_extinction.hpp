// Extinction of a size distribution by integration along a path in the
// complex size-parameter plane.
//
// sigma_ext = int_0^inf Q_ext(x) pi r^2 n(r) dr,  x = 2 pi r / lambda, and
// Q_ext(x) = 4 Re S(0; x) / x^2 (optical theorem).  S(0; x) is analytic in
// Im x >= 0 for a passive sphere (mie/forward_amplitude.hpp), and so is
// pi r^2 n(r) for the analytic families (modified gamma, log-normal; tables
// and bounded power laws are analytic only piece by piece, and take the
// segmented route of segmented_contour.hpp).  By Cauchy's theorem the integral over
// [0, x_max] equals the integral along any path from 0 to x_max that stays
// above the real axis:
//
//     sigma_ext = Re [ int_P  4 S(0; x) / x^2  pi r^2 n(r) dr ],
//     P: x(t) = t + i h(t),  h(t) = H tanh(theta t / H),  t in [0, x_max],
//        then straight down from x_max + i h(x_max) to x_max,
//
// plus the tail beyond x_max, bounded by the exact omitted moment.  At height
// h the resonances of nearly lossless drops (poles at distance ~ their width
// below the axis) and the ripple of period ~0.8 in x are smoothed away
// (damped like e^{-2 pi h / 0.8}), so a smooth Gauss-Kronrod rule converges
// where the real-axis rule cannot resolve the resonances at all (bulk_optics.hpp
// reports them as an error instead): heavy advection fog at 550 nm to 1e-9 in
// 869 evaluations of S(0), ~7 ms on one core (validation/bench/weather_speed).
//
// Reported error: the quadrature part sum |K - G| over panels (61-point
// Kronrod, embedded 30-point Gauss; verified by halving every panel when the
// ripple left at height H is not far below the tolerance, see the .cpp); the
// tail part; and a rounding part: S(0) cancels by ~e^{2h} in the upper
// half-plane, so ForwardAmplitude::rounding_bound() is integrated along the
// path.  S(0) is summed in double for tolerances >= 1e-9 at h <= 4 (bound
// ~1e-11 relative), in long double otherwise.  theta keeps the continued
// density well behaved: exp(-b t^gamma) needs gamma x arg(r) small, a
// log-normal needs arg(r) small against ln(sigma_g).
#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <string>

#include "attenuvis/mie/forward_amplitude.hpp"
#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// The path and the tolerance of the contour integral.
struct ContourSettings {
  double rel_tolerance = 1e-9;  // quadrature part, relative to sigma_ext
  double height = 4.0;          // H: the path's height in x above the real axis
  // Distributions reaching further are left to bulk_optics (the real axis,
  // with Q_ext's large-x expansion above x = 1e4 and its ~0.7 % bound).
  // Up to S(0)'s range: the cost grows ~x_max^2, but Marshall-Palmer rain at
  // 8 mm/h then takes 0.36 s at 1.55 um (x_max 2.4e4) and 2.5 s at 550 nm
  // (6.8e4) for a certified 1e-9, against 1.45 s and 0.53 s for the real
  // axis's 0.7 % (docs/guide/optics-tables.md).  3e5 takes Marshall-Palmer
  // rain up to about 75 mm/h down to 200 nm (8 mm/h there: x_max 1.9e5,
  // 14 s on two cores, 270 MB).
  double max_x = mie::kForwardAmplitudeMaxX;
  double tail_fraction = 0;     // of the r^2 moment beyond x_max; 0: 2e-2 x rel_tolerance (bound ~4e-2 x)
  double initial_panel_heights = 25;  // first panels are this many H wide (in Re x)
  double tail_panel_fraction = 1e-5;  // beyond the radius leaving this much of the r^2 moment, ...
  double tail_panel_widths = 4;       // ... first panels are this many times wider
  int kronrod_points = 61;            // Gauss-Kronrod order per panel (15, 21, 31, 41, 51, 61)
  bool verify = false;  // always split every converged panel once and charge the change too (done anyway
                        // when the resonance ripple left at height H is not far below the tolerance)
  std::size_t max_evaluations = 400000;
  const std::atomic<bool>* cancel = nullptr;  // checked once per panel: Cancelled when set (cancel.hpp)

  double effective_tail_fraction() const { return tail_fraction > 0 ? tail_fraction : 2e-2 * rel_tolerance; }
};

// sigma_ext from the contour, with its error and what it cost.
struct ContourExtinction {
  IntegralEstimate extinction;  // 1/m, with quadrature, tail and rounding errors
  std::size_t evaluations = 0;
  double max_size_parameter = 0;
  double height = 0, angle = 0;  // H and theta used
  bool verified = false;         // the verification pass ran
  std::string method;
};

// Nothing (no throw) when the method does not apply: the density is not
// analytic, or x_max exceeds s.max_x.  Throws std::runtime_error if the
// tolerance cannot be met within s.max_evaluations.
std::optional<ContourExtinction> contour_extinction(const SizeDistribution& d, double wavelength_m,
                                                    std::complex<double> m, const ContourSettings& s = {});

}  // namespace attenuvis::weather
