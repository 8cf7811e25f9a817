// Bulk optics of core–shell particles (see attenuvis/weather/coated_optics.hpp).
#include "attenuvis/weather/coated_optics.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/layered.hpp"
#include "resonance.hpp"
#include "two_pass_bulk_optics.hpp"

namespace attenuvis::weather {
namespace {

// Outer radius over core radius: r_o³ (1 − f) = r³.
double outer_over_core(const Coating& c) { return std::cbrt(1.0 / (1.0 - c.shell_volume_fraction)); }

// Per core cross section: the cross sections refer to π r_o² = s² π r².
Efficiency per_core(const mie::Efficiencies<double>& q, double s2) {
  return Efficiency{q.qext * s2, q.qsca * s2, q.qabs * s2, q.g, q.qback * s2, {}, {}, {}};
}

}  // namespace

EfficiencyBatch coated_efficiency_batch(std::complex<double> core_m, const Coating& coating) {
  const double s = outer_over_core(coating);
  return [core_m, coating, s](const double* x, std::size_t n, Efficiency* out) {
    std::vector<double> xs(2 * n);
    std::vector<std::complex<double>> ms(2 * n);
    std::vector<std::size_t> offsets(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
      xs[2 * i] = x[i], xs[2 * i + 1] = s * x[i];
      ms[2 * i] = core_m, ms[2 * i + 1] = coating.shell_m;
      offsets[i + 1] = 2 * (i + 1);
    }
    std::vector<mie::Efficiencies<double>> q(n);
    mie::SpheresOptions one_thread;  // the integrals evaluate panels in parallel already
    one_thread.threads = 1;
    const auto errors = mie::layered_spheres(offsets.data(), xs.data(), ms.data(), n, q.data(), one_thread);
    if (!errors.empty()) throw std::invalid_argument(errors.front().message);
    for (std::size_t i = 0; i < n; ++i) out[i] = per_core(q[i], s * s);
  };
}

EfficiencyFunction coated_efficiencies(std::complex<double> core_m, const Coating& coating,
                                       const QuadratureSettings& settings) {
  const double s = outer_over_core(coating);
  mie::Extras extras;
  extras.coefficients = settings.legendre_moments >= 0;
  extras.angles_deg = settings.angles_deg;
  const int L = settings.legendre_moments;
  const bool polarised = settings.polarised && L >= 0;
  return [core_m, coating, s, extras, L, polarised](double x) {
    const auto sc = mie::layered_scatter({x, s * x}, {core_m, coating.shell_m}, extras);
    Efficiency e = per_core(sc.q, s * s);
    detail::add_angular_terms(sc, s * x, L, polarised, e);
    return e;
  };
}

BulkOptics coated_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> core_m,
                              const Coating& coating, const QuadratureSettings& s) {
  if (!(coating.shell_volume_fraction >= 0 && coating.shell_volume_fraction <= 0.999))
    throw std::invalid_argument("coated particles: the shell volume fraction must be in [0, 0.999]");
  QuadratureSettings q = s;
  q.asymptotic_x = 0;  // the large-x expansion is the homogeneous sphere's
  // The pole analysis (mie/resonances.hpp) is the homogeneous sphere's: a
  // coated particle's resonances lie elsewhere, so none are located, and the
  // method says that its errors are what the panels sample.
  const bool lossless_shell = s.estimate_resonances && coating.shell_m.imag() < resonance_free_k();
  q.estimate_resonances = false;
  BulkOptics b = detail::two_pass_bulk_optics(
      d, wavelength_m, coating.shell_m, coated_efficiency_batch(core_m, coating),
      [core_m, coating](const QuadratureSettings& a) { return coated_efficiencies(core_m, coating, a); }, q);
  b.method = "core-shell particles (layered-sphere Mie, shell " + io::significant(coating.shell_volume_fraction, 4) +
             " of the volume, index " + io::significant(coating.shell_m.real(), 6) + "+" +
             io::significant(coating.shell_m.imag(), 6) + "i); " + b.method;
  if (lossless_shell)
    b.method += "; the shell is nearly lossless (k < " + io::significant(resonance_free_k(), 3) +
                "): its resonances are not located, the errors cover what the panels sample";
  return b;
}

}  // namespace attenuvis::weather
