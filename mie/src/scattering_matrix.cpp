// Scattering-matrix elements, phase function and lidar quantities of a sphere
// (see attenuvis/mie/scattering_matrix.hpp).
#include "attenuvis/mie/scattering_matrix.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <boost/math/constants/constants.hpp>

namespace attenuvis::mie {

ScatteringMatrix scattering_matrix(double x, const Scattering<double>& s) {
  if (s.s1.size() != s.angles_deg.size() || s.s2.size() != s.angles_deg.size())
    throw std::invalid_argument("scattering_matrix: the amplitudes S1, S2 are missing (call scatter() "
                                "with extras.angles_deg)");
  if (!(x > 0) || !(s.q.qsca > 0))
    throw std::invalid_argument("scattering_matrix: need x > 0 and Qsca > 0");
  ScatteringMatrix out;
  out.angles_deg = s.angles_deg;
  const std::size_t n = s.angles_deg.size();
  out.s11.resize(n);
  out.s12.resize(n);
  out.s33.resize(n);
  out.s34.resize(n);
  out.phase.resize(n);
  const double to_phase = 4.0 / (x * x * s.q.qsca);
  for (std::size_t j = 0; j < n; ++j) {
    const double i1 = std::norm(s.s1[j]), i2 = std::norm(s.s2[j]);
    const std::complex<double> c = s.s2[j] * std::conj(s.s1[j]);
    out.s11[j] = 0.5 * (i2 + i1);
    out.s12[j] = 0.5 * (i2 - i1);
    out.s33[j] = c.real();
    out.s34[j] = c.imag();
    out.phase[j] = to_phase * out.s11[j];
  }
  return out;
}

ScatteringMatrix scattering_matrix(double x, std::complex<double> m, const std::vector<double>& angles_deg) {
  Extras ex;
  ex.angles_deg = angles_deg;
  return scattering_matrix(x, scatter(x, m, ex));
}

Lidar lidar(const Efficiencies<double>& q) {
  const double four_pi = 4 * boost::math::constants::pi<double>();
  Lidar out;
  out.backscatter_per_sr = q.qback / four_pi;
  out.lidar_ratio_sr = q.qback > 0 ? four_pi * q.qext / q.qback : std::numeric_limits<double>::infinity();
  out.linear_depolarisation = 0.0;
  return out;
}

}  // namespace attenuvis::mie
