// The double-precision entry points of the layered sphere (see
// attenuvis/mie/layered.hpp).  The series is the template of
// layered_series.hpp, instantiated here for double and, where the precision
// rule of layered_checks.hpp asks for it, for long double.
#include "attenuvis/mie/layered.hpp"

#include <stdexcept>
#include <string>

#include "layered_checks.hpp"
#include "layered_series.hpp"

namespace attenuvis::mie {
namespace {

Scattering<double> to_double(const Scattering<long double>& s) {
  Scattering<double> out;
  const Efficiencies<long double>& q = s.q;
  out.q = {double(q.qext), double(q.qsca), double(q.qabs), double(q.qback), double(q.qpr), double(q.g), q.terms};
  for (const auto& v : s.a) out.a.emplace_back(double(v.real()), double(v.imag()));
  for (const auto& v : s.b) out.b.emplace_back(double(v.real()), double(v.imag()));
  out.angles_deg = s.angles_deg;
  for (const auto& v : s.s1) out.s1.emplace_back(double(v.real()), double(v.imag()));
  for (const auto& v : s.s2) out.s2.emplace_back(double(v.real()), double(v.imag()));
  return out;
}

Scattering<double> evaluate(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                            bool conducting_core, const Extras& extras, const Options& options) {
  const std::size_t first = conducting_core ? 1 : 0;
  if (m.size() + first != x.size())
    throw std::invalid_argument("mie: a layered sphere needs one index per " +
                                std::string(conducting_core ? "shell (x.size() - 1)" : "size parameter") + ", got " +
                                std::to_string(x.size()) + " size parameters and " + std::to_string(m.size()) +
                                " indices");
  const std::string e = detail::layered_error(x.data(), m.data(), x.size(), first);
  if (!e.empty()) throw std::invalid_argument(e);
  // A layer of zero thickness is not there: the transfer across it is the
  // identity, which computed would only add rounding (an absorbing one even a
  // spurious absorption, large beside a weakly scattering particle).
  for (std::size_t l = 1; l < x.size(); ++l)
    if (x[l] == x[l - 1]) {
      std::vector<double> xs = x;
      std::vector<std::complex<double>> ms = m;
      xs.erase(xs.begin() + static_cast<std::ptrdiff_t>(l));
      ms.erase(ms.begin() + static_cast<std::ptrdiff_t>(l - first));
      return evaluate(xs, ms, conducting_core, extras, options);
    }
  // One layer: the homogeneous sphere itself (the same bits).
  if (x.size() == 1)
    return conducting_core ? scatter(x[0], PerfectConductor{}, extras, options) : scatter(x[0], m[0], extras, options);
  if (detail::layered_use_extended(x.data(), m.data(), x.size(), first, options)) {
    const std::vector<long double> xl(x.begin(), x.end());
    std::vector<std::complex<long double>> ml;
    for (const auto& v : m) ml.emplace_back(v.real(), v.imag());
    return to_double(detail::layered_series<long double>({xl.data(), ml.data(), x.size(), conducting_core}, extras,
                                                         options));
  }
  return detail::layered_series<double>({x.data(), m.data(), x.size(), conducting_core}, extras, options);
}

}  // namespace

Efficiencies<double> layered_sphere(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                    const Options& options) {
  return evaluate(x, m, false, Extras{}, options).q;
}

Scattering<double> layered_scatter(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                   const Extras& extras, const Options& options) {
  return evaluate(x, m, false, extras, options);
}

Efficiencies<double> layered_sphere(PerfectConductor, const std::vector<double>& x,
                                    const std::vector<std::complex<double>>& m, const Options& options) {
  return evaluate(x, m, true, Extras{}, options).q;
}

Scattering<double> layered_scatter(PerfectConductor, const std::vector<double>& x,
                                   const std::vector<std::complex<double>>& m, const Extras& extras,
                                   const Options& options) {
  return evaluate(x, m, true, extras, options);
}

}  // namespace attenuvis::mie
