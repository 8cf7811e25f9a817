// The double-precision Mie entry points (the product).  The series itself is
// the template in series.hpp, instantiated here for double.
#include <cmath>
#include <stdexcept>
#include <string>

#include "attenuvis/mie.hpp"
#include "series.hpp"
#include "sphere_checks.hpp"

namespace attenuvis::mie {
namespace {

void check_x(double x) {
  if (x >= detail::kMinX && x <= detail::kMaxX) return;  // common case: no message built
  const std::string e = detail::size_parameter_error(x);
  if (!e.empty()) throw std::invalid_argument(e);
}

void check_m(std::complex<double> m) {
  if (detail::index_in_domain(m)) return;  // common case: no message built, no hypot
  const std::string e = detail::refractive_index_error(m);
  if (!e.empty()) throw std::invalid_argument(e);
}

using detail::use_extended;

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
