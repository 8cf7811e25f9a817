// The bridge from attenuvis::mie to the bulk integrals (bulk_optics.hpp):
// Lorenz-Mie efficiencies as an EfficiencyFunction (one sphere per call) and an
// EfficiencyBatch (a panel's nodes per call, mie::spheres), and bulk_optics() with them.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"
#include "attenuvis/mie/spheres.hpp"
#include "attenuvis/weather/bulk_optics.hpp"
#include "resonance.hpp"
#include "bulk_components.hpp"
#include "two_pass_bulk_optics.hpp"

namespace attenuvis::weather {

namespace {

// The working precision of the bulk integrals (bulk_optics.hpp: mie_efficiencies).
mie::Options bulk_options(std::complex<double> m) {
  mie::Options options;
  if (std::abs(m - 1.0) >= 0.01) options.extended_above = 3e4;  // automatic precision: double-only up to there
  return options;
}

Efficiency from_mie(const mie::Efficiencies<double>& e) {
  return Efficiency{e.qext, e.qsca, e.qabs, e.g, e.qback, {}, {}, {}};
}

// mie::spheres() over a panel's nodes, on the calling thread (the integrals
// already evaluate panels in parallel).  A bad x throws as sphere() would.
EfficiencyBatch sphere_batch(std::complex<double> m, const mie::Options& options) {
  return [m, options](const double* x, std::size_t n, Efficiency* out) {
    mie::SpheresOptions so;
    so.options = options;
    so.threads = 1;
    std::vector<mie::Efficiencies<double>> q(n);
    const std::vector<mie::SphereError> errors = mie::spheres(x, m, n, q.data(), so);
    if (!errors.empty()) throw std::invalid_argument(errors.front().message);
    for (std::size_t i = 0; i < n; ++i) out[i] = from_mie(q[i]);
  };
}

}  // namespace

EfficiencyFunction mie_efficiencies(std::complex<double> m) {
  const mie::Options options = bulk_options(m);
  return [m, options](double x) { return from_mie(mie::sphere(x, m, options)); };
}

EfficiencyBatch mie_efficiency_batch(std::complex<double> m) { return sphere_batch(m, bulk_options(m)); }

EfficiencyFunction mie_efficiencies(std::complex<double> m, const QuadratureSettings& s) {
  if (s.legendre_moments < 0 && s.angles_deg.empty()) return mie_efficiencies(m);
  const mie::Options options = bulk_options(m);
  mie::Extras extras;
  extras.coefficients = s.legendre_moments >= 0;
  extras.angles_deg = s.angles_deg;
  const int L = s.legendre_moments;
  const bool polarised = s.polarised && L >= 0;
  return [m, options, extras, L, polarised](double x) {
    const auto sc = mie::scatter(x, m, extras, options);
    Efficiency e = from_mie(sc.q);
    detail::add_angular_terms(sc, x, L, polarised, e);
    return e;
  };
}

void detail::add_angular_terms(const mie::Scattering<double>& sc, double x, int L, bool polarised, Efficiency& e) {
  if (L >= 0) {
    e.moments = mie::phase_function_moments(sc, static_cast<std::size_t>(L));
    e.moments.resize(static_cast<std::size_t>(L) + 1, 0.0);  // above 2N they are exact zeros
  }
  if (!sc.angles_deg.empty()) e.phase = mie::scattering_matrix(x, sc).phase;
  if (polarised) {
    const auto ex = mie::scattering_matrix_expansion(sc, static_cast<std::size_t>(L));
    for (const auto* v : {&ex.alpha1, &ex.alpha2, &ex.alpha3, &ex.alpha4, &ex.beta1, &ex.beta2}) {
      std::vector<double> part = *v;
      part.resize(static_cast<std::size_t>(L) + 1, 0.0);
      e.expansion.insert(e.expansion.end(), part.begin(), part.end());
    }
  }
}

BulkOptics detail::two_pass_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                                        const EfficiencyBatch& cheap_batch,
                                        const std::function<EfficiencyFunction(const QuadratureSettings&)>& angular,
                                        const QuadratureSettings& s) {
  if (s.legendre_moments < 0 && s.angles_deg.empty()) return integrate_bulk_optics(d, wavelength_m, cheap_batch, s, m);
  // Pass A: everything but the angular quantities, with cheap evaluations.
  QuadratureSettings cheap = s;
  cheap.legendre_moments = -1;
  cheap.angles_deg.clear();
  cheap.polarised = false;
  BulkOptics out = integrate_bulk_optics(d, wavelength_m, cheap_batch, cheap, m);
  if (!out.scattering_computed) return out;  // large-x expansion used: no angular quantities either
  // Pass B: the angular quantities.  Their sigma_sca serves only as the
  // denominator of chi_l and p(theta), so pass B integrates everything to the
  // angular tolerance; the reported sigma, g and beta_pi come from pass A.
  QuadratureSettings angular_settings = s;
  angular_settings.backscatter = false;
  angular_settings.rel_tolerance = detail::angular_tolerance(s);
  angular_settings.angular_tolerance = detail::angular_tolerance(s);
  // The tails as pass A cuts them: p(0) Q_sca grows like x^2, so the bound on
  // the omitted drops (sampled maximum x omitted moment) needs the finer cut.
  if (s.tail_fraction <= 0) angular_settings.tail_fraction = 1e-3 * s.rel_tolerance;
  const BulkOptics b = integrate_bulk_optics(d, wavelength_m, angular(angular_settings), angular_settings, m);
  out.moments = b.moments;
  out.moments_error = b.moments_error;
  out.angles_deg = b.angles_deg;
  out.phase = b.phase;
  out.phase_error = b.phase_error;
  out.expansion = b.expansion;
  out.expansion_error = b.expansion_error;
  out.evaluations += b.evaluations;
  if (!b.shortfall.empty()) out.shortfall += (out.shortfall.empty() ? "" : "; ") + ("angular pass: " + b.shortfall);
  out.method += "; moments/phase function in a second pass (" + std::to_string(b.evaluations) +
                " evaluations with angular terms, rel. tol " + io::significant(angular_settings.rel_tolerance, 3) +
                ")";
  return out;
}

BulkOptics mie_bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                           const QuadratureSettings& s) {
  return detail::two_pass_bulk_optics(d, wavelength_m, m, mie_efficiency_batch(m),
                                      [m](const QuadratureSettings& q) { return mie_efficiencies(m, q); }, s);
}

BulkOptics bulk_optics(const SizeDistribution& d, double wavelength_m, std::complex<double> m,
                       const QuadratureSettings& s) {
  if (s.legendre_moments >= 0 || !s.angles_deg.empty()) return mie_bulk_optics(d, wavelength_m, m, s);
  return integrate_bulk_optics(d, wavelength_m, sphere_batch(m, mie::Options{}), s, m);
}

}  // namespace attenuvis::weather
