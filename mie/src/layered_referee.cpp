// The 50-digit instantiation of the layered-sphere series (see
// attenuvis/mie/layered_referee.hpp).
#include "attenuvis/mie/layered_referee.hpp"

#include <stdexcept>
#include <string>

#include "layered_checks.hpp"
#include "layered_series.hpp"

namespace attenuvis::mie {
namespace {

// The problem converted exactly to 50 digits (the storage of the view).
struct RefereeLayers {
  std::vector<Referee> x;
  std::vector<Complex<Referee>> m;
  bool conducting_core;
  RefereeLayers(const std::vector<double>& xd, const std::vector<std::complex<double>>& md, bool conductor)
      : conducting_core(conductor) {
    const std::size_t first = conductor ? 1 : 0;
    if (md.size() + first != xd.size() || (conductor && xd.size() < 2))
      throw std::invalid_argument("mie layered referee: one index per layer (per shell on a conductor) needed");
    const std::string e = detail::layered_error(xd.data(), md.data(), xd.size(), first);
    if (!e.empty()) throw std::invalid_argument(e);
    for (double v : xd) x.emplace_back(v);
    for (const auto& v : md) m.emplace_back(Referee(v.real()), Referee(v.imag()));
  }
  detail::LayeredProblem<Referee> view() const { return {x.data(), m.data(), x.size(), conducting_core}; }
};

}  // namespace

Scattering<Referee> layered_scatter_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                            const Extras& extras, const Options& options) {
  return detail::layered_series<Referee>(RefereeLayers(x, m, false).view(), extras, options);
}

Efficiencies<Referee> layered_sphere_referee(const std::vector<double>& x, const std::vector<std::complex<double>>& m,
                                             const Options& options) {
  return layered_scatter_referee(x, m, Extras{}, options).q;
}

Efficiencies<Referee> layered_sphere_referee(PerfectConductor, const std::vector<double>& x,
                                             const std::vector<std::complex<double>>& m, const Options& options) {
  return detail::layered_series<Referee>(RefereeLayers(x, m, true).view(), Extras{}, options).q;
}

}  // namespace attenuvis::mie
