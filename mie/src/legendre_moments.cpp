// Legendre moments and scattering-matrix expansion in double precision (the
// algorithm: attenuvis/mie/detail/legendre_moments_impl.hpp).
#include "attenuvis/mie/legendre_moments.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <boost/math/special_functions/cos_pi.hpp>

#include "attenuvis/mie/detail/legendre_moments_impl.hpp"
#include "attenuvis/mie/legendre_moments_referee.hpp"

namespace attenuvis::mie {

std::vector<double> phase_function_moments(const Scattering<double>& s, std::size_t max_order) {
  return detail::legendre_moments<double>(s.a, s.b, max_order);
}

std::vector<double> phase_function_moments(double x, std::complex<double> m, std::size_t max_order) {
  Extras ex;
  ex.coefficients = true;
  return phase_function_moments(scatter(x, m, ex), max_order);
}

ScatteringMatrixExpansion<double> scattering_matrix_expansion(const Scattering<double>& s,
                                                              std::size_t max_order) {
  return detail::gsf_coefficients<double>(s.a, s.b, max_order);
}

std::vector<double> phase_function_from_moments(const std::vector<double>& chi,
                                                const std::vector<double>& angles_deg) {
  std::vector<double> p(angles_deg.size());
  for (std::size_t j = 0; j < angles_deg.size(); ++j) {
    const double deg = angles_deg[j];
    if (!(deg >= 0 && deg <= 180))
      throw std::invalid_argument("phase_function_from_moments: angle " + std::to_string(j) +
                                  " is not in [0, 180] degrees");
    // s = sin²(θ/2) keeps μ = 1 − 2s exact near the forward peak; there (s <= ¼)
    // Bonnet's recurrence runs on Dₗ = Pₗ − Pₗ₋₁ (see legendre_moments_impl.hpp).
    const double half_sin = boost::math::sin_pi(deg / 360.0), s = half_sin * half_sin;
    double p0 = 1, p1 = 1 - 2 * s, d = -2 * s, sum = 0;
    for (std::size_t l = 0; l < chi.size(); ++l) {
      sum += double(2 * l + 1) * chi[l] * p0;
      const double k1 = double(2 * l + 3) / double(l + 2), k2 = double(l + 1) / double(l + 2);
      if (s <= 0.25) {
        d = k2 * d - k1 * 2 * s * p1;
        p0 = p1;
        p1 += d;
      } else {
        const double next = k1 * (p1 - 2 * s * p1) - k2 * p0;
        p0 = p1;
        p1 = next;
      }
    }
    p[j] = sum;
  }
  return p;
}

void gauss_legendre_half_rule(std::size_t order, std::vector<double>& theta, std::vector<double>& weight) {
  const detail::HalfGaussLegendre<double> r = detail::half_gauss_legendre<double>(order);
  theta.resize(r.s.size());
  weight = r.w;
  for (std::size_t k = 0; k < r.s.size(); ++k) theta[k] = 2 * std::asin(std::sqrt(r.s[k]));
}

}  // namespace attenuvis::mie
