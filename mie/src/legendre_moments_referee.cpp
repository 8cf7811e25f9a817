// The 50-digit instantiation of the Legendre-moment code (see
// attenuvis/mie/legendre_moments_referee.hpp).
#include "attenuvis/mie/legendre_moments_referee.hpp"

#include "attenuvis/mie/detail/legendre_moments_impl.hpp"

namespace attenuvis::mie {

std::vector<Referee> phase_function_moments_referee(const Scattering<Referee>& s, std::size_t max_order) {
  return detail::legendre_moments<Referee>(s.a, s.b, max_order);
}

ScatteringMatrixExpansion<Referee> scattering_matrix_expansion_referee(const Scattering<Referee>& s,
                                                                       std::size_t max_order) {
  return detail::gsf_coefficients<Referee>(s.a, s.b, max_order);
}

void gauss_legendre_half_rule_referee(std::size_t order, std::vector<Referee>& theta,
                                      std::vector<Referee>& weight) {
  const detail::HalfGaussLegendre<Referee> r = detail::half_gauss_legendre<Referee>(order);
  theta.resize(r.s.size());
  weight = r.w;
  for (std::size_t k = 0; k < r.s.size(); ++k) theta[k] = 2 * asin(sqrt(r.s[k]));
}

}  // namespace attenuvis::mie
