// The external mixture of bulk optics (aerosol_optics.hpp: external_mixture):
// extensive quantities add, normalised ones are weighted by sigma_sca.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "attenuvis/io/check.hpp"
#include "attenuvis/weather/aerosol_optics.hpp"
#include "bulk_components.hpp"

namespace attenuvis::weather {
namespace {

// to += n e, every part of the estimate (the structured binding names each
// member, so a part added to IntegralEstimate does not compile until it is here).
void add_scaled(IntegralEstimate& to, const IntegralEstimate& e, double n) {
  auto& [value, quadrature, tail, asymptotic, resonance, rounding] = to;
  const auto& [e_value, e_quadrature, e_tail, e_asymptotic, e_resonance, e_rounding] = e;
  value += n * e_value;
  quadrature += n * e_quadrature;
  tail += n * e_tail;
  asymptotic += n * e_asymptotic;
  resonance += n * e_resonance;
  rounding += n * e_rounding;
}

// A quantity normalised by sigma_sca (g, chi_l, p(theta), the expansion's
// coefficients): v = sum n_j v_j S_j / S.  Its numerator's error is bounded
// by sum n_j (err v_j S_j + |v_j| err S_j), and v's by (err_num + |v| err S) / S.
struct Normalised {
  const std::vector<const BulkOptics*>& optics;
  const std::vector<double>& numbers;
  double sca, sca_error;
  template <class Value>
  void operator()(Value value_of, double& value, double& error) const {
    double num = 0, num_error = 0;
    for (std::size_t j = 0; j < optics.size(); ++j) {
      const auto [v, e] = value_of(*optics[j]);
      const double s = optics[j]->scattering.value, se = optics[j]->scattering.error();
      num += numbers[j] * v * s;
      num_error += numbers[j] * (e * s + std::abs(v) * se);
    }
    value = sca > 0 ? num / sca : 0;
    error = sca > 0 ? (num_error + std::abs(value) * sca_error) / sca : 0;
  }
};

// The expansion's coefficient vectors, read only, in detail::expansion_parts' order.
std::array<const std::vector<double>*, detail::kExpansionParts> coefficients(const MatrixExpansion& e) {
  const auto& [alpha1, alpha2, alpha3, alpha4, beta1, beta2] = e;
  return {&alpha1, &alpha2, &alpha3, &alpha4, &beta1, &beta2};
}

// A vector of normalised values (moments, phase, an expansion coefficient),
// element by element; `pick` selects the (values, errors) of one part.
template <class Pick>
void mix_vector(const Normalised& mix, Pick pick, std::vector<double>& values, std::vector<double>& errors) {
  const std::size_t n = pick(*mix.optics.front()).first->size();
  values.assign(n, 0.0);
  errors.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    mix([&](const BulkOptics& b) { return std::pair{(*pick(b).first)[i], (*pick(b).second)[i]}; }, values[i],
        errors[i]);
}

void mix_angular(const Normalised& mix, BulkOptics& out) {
  const BulkOptics& first = *mix.optics.front();
  mix_vector(mix, [](const BulkOptics& b) { return std::pair{&b.moments, &b.moments_error}; }, out.moments,
             out.moments_error);
  out.angles_deg = first.angles_deg;
  mix_vector(mix, [](const BulkOptics& b) { return std::pair{&b.phase, &b.phase_error}; }, out.phase, out.phase_error);
  const auto values = detail::expansion_parts(out.expansion);
  const auto errors = detail::expansion_parts(out.expansion_error);
  for (int k = 0; k < detail::kExpansionParts; ++k)
    mix_vector(
        mix, [k](const BulkOptics& b) { return std::pair{coefficients(b.expansion)[k], coefficients(b.expansion_error)[k]}; },
        *values[k], *errors[k]);
}

}  // namespace

BulkOptics external_mixture(const std::vector<const BulkOptics*>& optics, const std::vector<double>& numbers) {
  ATTENUVIS_CHECK(!optics.empty());
  ATTENUVIS_CHECK_EQ(optics.size(), numbers.size());
  BulkOptics out;
  out.scattering_computed = true;
  out.backscatter_computed = true;
  for (std::size_t j = 0; j < optics.size(); ++j) {
    const BulkOptics& b = *optics[j];
    ATTENUVIS_CHECK(numbers[j] >= 0);
    add_scaled(out.extinction, b.extinction, numbers[j]);
    add_scaled(out.scattering, b.scattering, numbers[j]);
    add_scaled(out.absorption, b.absorption, numbers[j]);
    add_scaled(out.backscatter, b.backscatter, numbers[j]);
    out.evaluations += b.evaluations;
    out.resonances_located += b.resonances_located;
    out.resonances_resolved += b.resonances_resolved;
    out.max_size_parameter = std::max(out.max_size_parameter, b.max_size_parameter);
    out.scattering_computed = out.scattering_computed && b.scattering_computed;
    out.backscatter_computed = out.backscatter_computed && b.backscatter_computed;
    if (!b.shortfall.empty()) out.shortfall += (out.shortfall.empty() ? "" : "; ") + b.shortfall;
  }
  if (!out.backscatter_computed) out.backscatter = {};
  out.method = "external mixture of " + std::to_string(optics.size()) + " populations, " +
               std::to_string(out.evaluations) + " evaluations in all; each by " + optics.front()->method;
  const double ext = out.extinction.value, sca = out.scattering.value;
  if (!out.scattering_computed || !(ext > 0)) return out;
  out.albedo = sca / ext;
  out.albedo_error = (out.scattering.error() + out.albedo * out.extinction.error()) / ext;
  const Normalised mix{optics, numbers, sca, out.scattering.error()};
  mix([](const BulkOptics& b) { return std::pair{b.asymmetry, b.asymmetry_error}; }, out.asymmetry,
      out.asymmetry_error);
  if (out.backscatter_computed && out.backscatter.value > 0) {
    const double beta = out.backscatter.value;
    out.lidar_ratio = ext / beta;
    out.lidar_ratio_error = out.lidar_ratio * (out.extinction.error() / ext + out.backscatter.error() / beta);
  }
  mix_angular(mix, out);
  if (optics.size() == 1) {
    // One population: the normalised quantities are its own, with their own
    // (tighter) errors; only the extensive ones were scaled.
    const BulkOptics& b = *optics.front();
    out.asymmetry_error = b.asymmetry_error;
    out.moments_error = b.moments_error;
    out.phase_error = b.phase_error;
    out.expansion_error = b.expansion_error;
  }
  return out;
}

}  // namespace attenuvis::weather
