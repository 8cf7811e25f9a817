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
// Double is enough, to the rounding level of the result, for every index the
// stress grid holds (tests/mie/test_mie_referee.cpp) up to kDoubleUpTo, except
// close to m = 1 (trap psi-zero, series.hpp): at a zero of ψₙ(x) the
// difference recurrence for yₙ(mx) − yₙ(x) inherits the cancellation of
// yₙ(x), and with |m − 1| <= 1e-6 the result misses 1e-10 by up to 3× in
// double (measured at x = 4.4934…, 6.9879…, 15.03…, 41.9…), while at
// |m − 1| = 1e-4 the double error is still below 1e-11.  Above kDoubleUpTo
// the recurrences run through ~x oscillations and in double their rounding
// errors accumulate to ~√N·ε in every aₙ; Qback, an alternating sum that
// cancels by a factor ~x, would be off by up to 1e-8 at x = 1e6 (trap
// back-cancellation).
constexpr double kDoubleUpTo = 1e4;
constexpr double kNearOne = 1e-2;

bool use_extended(double x, std::complex<double> m, bool pec, const Options& options) {
  if (options.precision) return *options.precision == Precision::extended;
  if (x <= options.extended_above) return false;
  if (x > kDoubleUpTo) return true;
  return !pec && std::norm(m - 1.0) < kNearOne * kNearOne;
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
