// Argument checks and the automatic choice of working precision of the
// double-precision entry points, shared by sphere()/scatter()
// (sphere_double.cpp) and the batch spheres() (spheres.cpp).  Private to the
// mie library.
#pragma once

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "attenuvis/mie.hpp"

namespace attenuvis::mie::detail {

// "" for a valid size parameter, else the message.
inline std::string size_parameter_error(double x) {
  if (std::isfinite(x) && x > 0.0 && x <= 2e7) return {};
  std::ostringstream os;
  os.precision(17);
  os << "mie: size parameter x must be finite and in (0, 2e7], got " << x;
  return os.str();
}

// "" for a valid refractive index, else the message.
inline std::string refractive_index_error(std::complex<double> m) {
  if (std::isfinite(m.real()) && std::isfinite(m.imag()) && m.real() >= 0.0 && m.imag() >= 0.0 &&
      m != std::complex<double>(0.0))
    return {};
  std::ostringstream os;
  os.precision(17);
  os << "mie: refractive index m = n + ik needs finite n >= 0, k >= 0 (k > 0 absorbs) and m != 0, got "
     << m.real() << (m.imag() < 0 ? " - " : " + ") << std::abs(m.imag()) << "i";
  return os.str();
}

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
