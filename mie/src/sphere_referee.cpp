// The 50-digit instantiation of the Mie series (see attenuvis/mie/referee.hpp).
#include "attenuvis/mie/referee.hpp"

#include <stdexcept>

#include "series.hpp"

namespace attenuvis::mie {
namespace {

void check(const Referee& x, const Complex<Referee>& m) {
  if (!(x > 0) || x > 2e7) throw std::invalid_argument("mie referee: x must be in (0, 2e7]");
  if (m.real() < 0 || m.imag() < 0 || (m.real() == 0 && m.imag() == 0))
    throw std::invalid_argument("mie referee: m = n + ik needs n >= 0, k >= 0, m != 0");
}

}  // namespace

Scattering<Referee> scatter_referee(const Referee& x, const Complex<Referee>& m, const Extras& extras,
                                    const Options& options) {
  check(x, m);
  return detail::mie_series<Referee>(x, m, false, extras, options);
}

Scattering<Referee> scatter_referee(const Referee& x, PerfectConductor, const Extras& extras,
                                    const Options& options) {
  check(x, Complex<Referee>(1));
  return detail::mie_series<Referee>(x, Complex<Referee>(1), true, extras, options);
}

Efficiencies<Referee> sphere_referee(double x, std::complex<double> m, const Options& options) {
  return scatter_referee(Referee(x), Complex<Referee>(Referee(m.real()), Referee(m.imag())), Extras{}, options).q;
}

Efficiencies<Referee> sphere_referee(const std::string& x, const std::string& m_re, const std::string& m_im,
                                     const Options& options) {
  return scatter_referee(Referee(x), Complex<Referee>(Referee(m_re), Referee(m_im)), Extras{}, options).q;
}

}  // namespace attenuvis::mie
