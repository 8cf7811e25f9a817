// The bound on the extinction of the radii an integral leaves out, shared by
// the real-axis rule (bulk_optics.cpp) and the contour rule (contour_extinction.cpp).
#pragma once

#include <algorithm>

#include <boost/math/constants/constants.hpp>

namespace attenuvis::weather::detail {

// |Q_ext| <= max(4, 2 max sampled |Q_ext|) over the omitted radii, times pi
// times their exact r^2 moment.  Q_ext of a sphere stays below 4 for the
// refractive indices of water and ice (its first maximum, near x (n-1) = 2, is
// ~3.2 for n = 1.33); the factor 2 covers what the samples missed.  The tails
// hold a small fraction of the r^2 moment (1e-3 of the tolerance by default),
// so this bound is never limiting.
inline double extinction_tail_bound(double q_max_sampled, double omitted_r2_moment) {
  const double q_bound = std::max(4.0, 2 * q_max_sampled);
  return q_bound * boost::math::constants::pi<double>() * omitted_r2_moment;
}

}  // namespace attenuvis::weather::detail
