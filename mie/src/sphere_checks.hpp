// Argument checks and the automatic choice of working precision of the
// double-precision entry points, shared by sphere()/scatter()
// (sphere_double.cpp), the batch spheres() (spheres.cpp) and its lanes
// (sphere_lanes.cpp), which must route every sphere as sphere() would.
// Private to the mie library.
#pragma once

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie::detail {

// The domain of sphere(), scatter() and spheres() (documented in
// attenuvis/mie.hpp): what tests/mie/test_mie_referee.cpp checks against the
// 50-digit referee (x = 1e-8 ... 1e6, n = 0 ... 10, k = 0 ... 1000, |m| from
// 0.5 (m = 0.5i) on), plus large |m| up to 1e6, checked against the perfect
// conductor it tends to (tests/mie/test_mie_core.cpp).  Outside it the core
// fails rather than degrades: x < ~1.4e-154 squares to 0 (NaN), |m| ~ 1e154
// overflows |m x|², |m| -> 0 divides by m.
constexpr double kMinX = 1e-8, kMaxX = 1e6;
constexpr double kMaxIndex = 1e6, kMinAbsIndex = 0.5;

// "" for a valid size parameter, else the message.
inline std::string size_parameter_error(double x) {
  if (std::isfinite(x) && x >= kMinX && x <= kMaxX) return {};
  std::ostringstream os;
  os.precision(17);
  os << "mie: size parameter x must be finite and in [" << kMinX << ", " << kMaxX << "], got " << x;
  return os.str();
}

// "" for a valid refractive index, else the message.
inline std::string refractive_index_error(std::complex<double> m) {
  const double n = m.real(), k = m.imag();
  if (std::isfinite(n) && std::isfinite(k) && n >= 0.0 && k >= 0.0 && n <= kMaxIndex && k <= kMaxIndex &&
      std::hypot(n, k) >= kMinAbsIndex)
    return {};
  std::ostringstream os;
  os.precision(17);
  os << "mie: refractive index m = n + ik needs finite 0 <= n <= " << kMaxIndex << ", 0 <= k <= " << kMaxIndex
     << " (k > 0 absorbs) and |m| >= " << kMinAbsIndex << ", got " << n << (k < 0 ? " - " : " + ")
     << std::abs(k) << "i";
  return os.str();
}

// m in the domain, tested without building a message or calling hypot (the
// common case).  Conservative near |m| = 0.5: an index this does not accept
// goes through refractive_index_error(), which decides exactly and explains.
// (NaN fails every comparison, so it is never accepted here.)
inline bool index_in_domain(std::complex<double> m) {
  const double n = m.real(), k = m.imag();
  return n >= 0.0 && k >= 0.0 && n <= kMaxIndex && k <= kMaxIndex &&
         n * n + k * k >= 1.000001 * kMinAbsIndex * kMinAbsIndex;
}

// Options under which sphere() runs the lanes' series wherever the default
// rule of use_extended() (below) chooses double: converged terms, automatic
// precision.  extended_above only moves more spheres to double, where they
// are evaluated as by the default rule's double path (same bits), so it does
// not exclude the lanes; the spheres it moves go through sphere() itself.
inline bool lane_options(const Options& o) { return o.terms == TermRule::converged && !o.precision; }

// Where the recurrences need extended precision (Options::precision unset).
// Double is enough, to well within 1e-10 of the 50-digit referee, except:
//  * above kDoubleUpTo: the recurrences run through ~x oscillations and in
//    double their rounding errors accumulate to ~√N·ε in every aₙ; Qback, an
//    alternating sum that cancels by ~x, is then off by ~1e-11 at x = 3e4 and
//    1e5 (trap back-cancellation); at x = 1e4 the largest error over the 49
//    indices of the stress grid is 1.2e-12.
//  * |m − 1| < kPsiZero: at a zero of ψₙ(x) the difference recurrence for
//    yₙ(mx) − yₙ(x) inherits the cancellation of yₙ(x) (trap psi-zero); the
//    double error there grows like 1/|m − 1|: measured at the zeros of
//    tests/mie/test_mie_referee.cpp, 8e-11 at |m − 1| = 1e-6, 8e-12 at 1e-5,
//    6e-13 at 1e-4 (extended: 3e-13 throughout).
//  * |m − 1| < kNearOne and x > kNearOneUpTo: there Qback ~ 1e-9 Qext, and its
//    relative error in double grows with x: 1e-12 at x = 1e3, 1e-11 at 1e4
//    (m = 1.001), against 4e-14 and 2e-13 with extended recurrences.
constexpr double kDoubleUpTo = 1e4;
constexpr double kPsiZero = 5e-5;
constexpr double kNearOne = 1e-2;
constexpr double kNearOneUpTo = 1e3;

inline bool use_extended(double x, std::complex<double> m, bool pec, const Options& options) {
  if (options.precision) return *options.precision == Precision::extended;
  if (x <= options.extended_above) return false;
  if (x > kDoubleUpTo) return true;
  if (pec) return false;
  const double d2 = std::norm(m - 1.0);
  return d2 < kPsiZero * kPsiZero || (d2 < kNearOne * kNearOne && x > kNearOneUpTo);
}

}  // namespace attenuvis::mie::detail
