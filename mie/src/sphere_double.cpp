// The double-precision Mie entry points (the product).  The series itself is
// the template in attenuvis/mie/series.hpp, instantiated here for double.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/series.hpp"

namespace attenuvis::mie {
namespace {

void check_x(double x) {
  if (!std::isfinite(x) || x <= 0.0 || x > 2e7) {
    std::ostringstream os;
    os.precision(17);
    os << "mie: size parameter x must be finite and in (0, 2e7], got " << x;
    throw std::invalid_argument(os.str());
  }
}

void check_m(std::complex<double> m) {
  if (!std::isfinite(m.real()) || !std::isfinite(m.imag()) || m.real() < 0.0 || m.imag() < 0.0 ||
      m == std::complex<double>(0.0)) {
    std::ostringstream os;
    os.precision(17);
    os << "mie: refractive index m = n + ik needs finite n >= 0, k >= 0 (k > 0 absorbs) and m != 0, got "
       << m.real() << (m.imag() < 0 ? " - " : " + ") << std::abs(m.imag()) << "i";
    throw std::invalid_argument(os.str());
  }
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

bool use_extended(double x, std::complex<double> m, bool pec, const Options& options) {
  if (options.precision) return *options.precision == Precision::extended;
  if (x <= options.extended_above) return false;
  if (x > kDoubleUpTo) return true;
  if (pec) return false;
  const double d2 = std::norm(m - 1.0);
  return d2 < kPsiZero * kPsiZero || (d2 < kNearOne * kNearOne && x > kNearOneUpTo);
}

}  // namespace

std::size_t wiscombe_terms(double x) {
  check_x(x);
  return detail::wiscombe_term_count(x);
}

Efficiencies<double> sphere(double x, std::complex<double> m, const Options& options) {
  return scatter(x, m, Extras{}, options).q;
}

Efficiencies<double> sphere(double x, PerfectConductor pec, const Options& options) {
  return scatter(x, pec, Extras{}, options).q;
}

Scattering<double> scatter(double x, std::complex<double> m, const Extras& extras, const Options& options) {
  check_x(x);
  check_m(m);
  if (use_extended(x, m, false, options))
    return detail::mie_series<double, long double>(x, m, false, extras, options);
  return detail::mie_series<double>(x, m, false, extras, options);
}

Scattering<double> scatter(double x, PerfectConductor, const Extras& extras, const Options& options) {
  check_x(x);
  if (use_extended(x, 1.0, true, options))
    return detail::mie_series<double, long double>(x, std::complex<double>(1.0), true, extras, options);
  return detail::mie_series<double>(x, std::complex<double>(1.0), true, extras, options);
}

}  // namespace attenuvis::mie
