// The 50-digit instantiation of the layered-sphere series (see
// attenuvis/mie/layered_referee.hpp).
#include "attenuvis/mie/layered_referee.hpp"

#include <stdexcept>
#include <string>

#include "layered_checks.hpp"
#include "layered_series.hpp"

namespace attenuvis::mie {
namespace {

detail::LayeredProblem<Referee> problem(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                        bool conducting_core) {
  const std::size_t first = conducting_core ? 1 : 0;
  if (m.size() + first != x.size() || (conducting_core && x.size() < 2))
    throw std::invalid_argument("mie layered referee: one index per layer (per shell on a conductor) needed");
  const std::string e = detail::layered_error(x.data(), m.data(), x.size(), first);
  if (!e.empty()) throw std::invalid_argument(e);
  detail::LayeredProblem<Referee> p;
  p.conducting_core = conducting_core;
  for (double v : x) p.x.emplace_back(v);
  if (conducting_core) p.m.emplace_back(Referee(1));
  for (const auto& v : m) p.m.emplace_back(Referee(v.real()), Referee(v.imag()));
  return p;
}

}  // namespace

Scattering<Referee> layered_scatter_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                            const Extras& extras, const Options& options) {
  return detail::layered_series<Referee>(problem(x, m, false), extras, options);
}

Efficiencies<Referee> layered_sphere_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                             const Options& options) {
  return layered_scatter_referee(x, m, Extras{}, options).q;
}

Efficiencies<Referee> layered_sphere_referee(PerfectConductor, const std::vector<double>& x,
                                             const std::vector<std::complex<double>>& m, const Options& options) {
  return detail::layered_series<Referee>(problem(x, m, true), Extras{}, options).q;
}

}  // namespace attenuvis::mie
