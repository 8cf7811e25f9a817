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

void check_sizes(std::size_t x_size, std::size_t m_size, bool conducting_core) {
  const std::size_t first = conducting_core ? 1 : 0;
  if (m_size + first != x_size)
    throw std::invalid_argument("mie: a layered sphere needs one index per " +
                                std::string(conducting_core ? "shell (x.size() - 1)" : "size parameter") + ", got " +
                                std::to_string(x_size) + " size parameters and " + std::to_string(m_size) + " indices");
}

Scattering<double> evaluate(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                            bool conducting_core, const Extras& extras, const Options& options) {
  check_sizes(x.size(), m.size(), conducting_core);
  const std::size_t first = conducting_core ? 1 : 0;
  const std::string e = detail::layered_error(x.data(), m.data(), x.size(), first);
  if (!e.empty()) throw std::invalid_argument(e);
  return detail::layered_evaluate(x.data(), m.data(), x.size(), conducting_core, extras, options);
}

}  // namespace

namespace detail {

Scattering<double> layered_evaluate(const double* x, const std::complex<double>* m, std::size_t layers,
                                    bool conducting_core, const Extras& extras, const Options& options) {
  const std::size_t first = conducting_core ? 1 : 0;
  // A layer of zero thickness is not there: the transfer across it is the
  // identity, which computed would only add rounding (an absorbing one even a
  // spurious absorption, large beside a weakly scattering particle).
  for (std::size_t l = 1; l < layers; ++l)
    if (x[l] == x[l - 1]) {
      std::vector<double> xs(x, x + layers);
      std::vector<std::complex<double>> ms(m, m + (layers - first));
      xs.erase(xs.begin() + static_cast<std::ptrdiff_t>(l));
      ms.erase(ms.begin() + static_cast<std::ptrdiff_t>(l - first));
      return layered_evaluate(xs.data(), ms.data(), xs.size(), conducting_core, extras, options);
    }
  // One layer: the homogeneous sphere itself (the same bits).
  if (layers == 1)
    return conducting_core ? scatter(x[0], PerfectConductor{}, extras, options) : scatter(x[0], m[0], extras, options);
  if (layered_use_extended(x, m, layers, first, options)) {
    const std::vector<long double> xl(x, x + layers);
    std::vector<std::complex<long double>> ml;
    for (std::size_t l = 0; l + first < layers; ++l) ml.emplace_back(m[l].real(), m[l].imag());
    return to_double(layered_series<long double>({xl.data(), ml.data(), layers, conducting_core}, extras, options));
  }
  return layered_series<double>({x, m, layers, conducting_core}, extras, options);
}

}  // namespace detail

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
