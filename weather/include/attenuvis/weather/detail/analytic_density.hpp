// The densities of the analytic families (size_distribution.hpp), written once
// for real radii (SizeDistribution::density) and for complex radii (their
// continuation, which contour_extinction.cpp integrates along).  Detail of
// the library, in a public header only for its tests.
#pragma once

#include <cmath>
#include <complex>
#include <optional>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather::detail {

// n = a t^alpha exp(-b t^gamma), t = r / r0; in log form so that it tends to
// 0 instead of inf * 0 at huge r.
template <class Radius>
Radius modified_gamma_density(const ModifiedGamma& g, Radius r) {
  const Radius t = r / g.r0;
  return g.a * std::exp(g.alpha * std::log(t) - g.b * std::pow(t, g.gamma));
}

// n = N / (sqrt(2 pi) ln(sg) r) exp(-(ln r - ln rg)^2 / (2 ln^2 sg)).
template <class Radius>
Radius log_normal_density(const LogNormal& l, Radius r) {
  const double s = std::log(l.sigma_g);
  const Radius z = (std::log(r) - std::log(l.median_radius_m)) / s;
  return l.number_per_m3 / (std::sqrt(2 * boost::math::constants::pi<double>()) * s * r) * std::exp(-0.5 * z * z);
}

// The density continued to complex r (m^-4), for the analytic families only
// (modified gamma, log-normal); nothing for the others.
std::optional<std::complex<double>> analytic_density(const SizeDistribution& d, std::complex<double> r_m);

}  // namespace attenuvis::weather::detail
