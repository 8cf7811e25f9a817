// Visibility and contrast (seed paper Eqs. "Koschmieder" and "Contrast Ratio").
//
//   C = exp(-sigma d)                  contrast ratio left after distance d
//   V = -ln(epsilon) / sigma           Koschmieder (1924) visibility at threshold epsilon:
//                                      epsilon = 0.02 gives 3.912/sigma (Kruse 1962, the seed's default),
//                                      epsilon = 0.05 gives 2.996/sigma (meteorological optical range, WMO).
#pragma once

#include <cmath>
#include <stdexcept>

namespace attenuvis::weather {

// Koschmieder's visibility V = -ln(threshold)/sigma, in metres.
inline double koschmieder_visibility_m(double sigma_per_m, double threshold = 0.02) {
  if (!(threshold > 0 && threshold < 1)) throw std::invalid_argument("contrast threshold must lie in (0, 1)");
  if (!(sigma_per_m > 0)) throw std::invalid_argument("visibility needs sigma > 0");
  return -std::log(threshold) / sigma_per_m;
}

// The sigma that gives visibility V at the threshold (inverse of the above).
inline double sigma_from_visibility_per_m(double visibility_m, double threshold = 0.02) {
  if (!(threshold > 0 && threshold < 1)) throw std::invalid_argument("contrast threshold must lie in (0, 1)");
  if (!(visibility_m > 0)) throw std::invalid_argument("visibility must be > 0");
  return -std::log(threshold) / visibility_m;
}

// The contrast left after a distance: C = exp(-sigma d).
inline double contrast_ratio(double sigma_per_m, double distance_m) { return std::exp(-sigma_per_m * distance_m); }

}  // namespace attenuvis::weather
