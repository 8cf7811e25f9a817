// Interpolation of refractive-index columns in wavelength, one rule for the
// water tables (refractive_index.cpp) and index files (index_file.cpp): n is
// linear in ln(lambda); k, which spans ten decades across the visible and
// infrared, is a power law (ln k linear in ln(lambda)) between neighbours that
// are both positive, else linear in ln(lambda).  The caller has checked that
// `at` lies within [w.front(), w.back()]; w increases strictly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "attenuvis/io/check.hpp"

namespace attenuvis::weather::detail {

// `at` moved onto [lo, hi] when it misses by no more than 1e-12 relative:
// a bound reached through a unit conversion (200e-6 m against a row read as
// 200 um, 0.2 um against 200 nm) is the bound, as the domains treat it
// (domains.cpp).  Further outside it is returned as is, for the caller to refuse.
inline double onto_range(double at, double lo, double hi) {
  if (at < lo && at >= lo * (1 - 1e-12)) return lo;
  if (at > hi && at <= hi * (1 + 1e-12)) return hi;
  return at;
}

// The bracketing rows lo = hi - 1 of `at` and its position t in ln(lambda) between them.
struct Bracket {
  std::size_t lo = 0, hi = 1;
  double t = 0;
};
inline Bracket bracket(const std::vector<double>& w, double at) {
  ATTENUVIS_CHECK_GE(w.size(), 2u);
  ATTENUVIS_CHECK(at >= w.front() && at <= w.back());
  std::size_t hi = static_cast<std::size_t>(std::upper_bound(w.begin(), w.end(), at) - w.begin());
  hi = std::clamp<std::size_t>(hi, 1, w.size() - 1);
  return {hi - 1, hi, std::log(at / w[hi - 1]) / std::log(w[hi] / w[hi - 1])};
}

inline double linear_in_log_wavelength(const std::vector<double>& w, const std::vector<double>& v, double at) {
  const Bracket b = bracket(w, at);
  return v[b.lo] + b.t * (v[b.hi] - v[b.lo]);
}

inline double power_law_in_log_wavelength(const std::vector<double>& w, const std::vector<double>& v, double at) {
  const Bracket b = bracket(w, at);
  if (v[b.lo] > 0 && v[b.hi] > 0) return std::exp(std::log(v[b.lo]) + b.t * std::log(v[b.hi] / v[b.lo]));
  return v[b.lo] + b.t * (v[b.hi] - v[b.lo]);
}

}  // namespace attenuvis::weather::detail
