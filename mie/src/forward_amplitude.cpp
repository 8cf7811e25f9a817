// S(0) at complex size parameter: see attenuvis/mie/forward_amplitude.hpp.
#include "attenuvis/mie/forward_amplitude.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "attenuvis/mie/lentz.hpp"

namespace attenuvis::mie {
namespace {

using R = long double;
using C = std::complex<long double>;

// Dₙ(z) for n = 0..N: downward recurrence D_{n−1} = n/z − 1/(Dₙ + n/z)
// (B&H eq. 4.89) from D_N taken from Lentz's continued fraction.
void log_derivatives(C z, std::size_t N, std::vector<C>& d) {
  d.assign(N + 1, C(0));
  const C inv_z = detail::recip(z);
  const C ratio = detail::riccati_psi_ratio<C, R>(N, [&](R k) { return k * inv_z; });
  d[N] = ratio - R(N) * inv_z;  // ψ_{N−1}/ψ_N = D_N + N/z
  for (std::size_t n = N; n >= 1; --n) d[n - 1] = R(n) * inv_z - detail::recip(d[n] + R(n) * inv_z);
}

void check(std::complex<double> x, std::complex<double> m) {
  const bool ok = std::isfinite(x.real()) && std::isfinite(x.imag()) && std::isfinite(m.real()) &&
                  std::isfinite(m.imag()) && x.real() > 0 && x.imag() >= 0 && x.imag() <= 20 &&
                  std::abs(x) <= 1e5 && m.real() > 0 && m.imag() >= 0 && std::abs(m - 1.0) >= 1e-6;
  if (!ok) {
    std::ostringstream os;
    os.precision(17);
    os << "mie::forward_amplitude: needs 0 < |x| <= 1e5, Re x > 0, 0 <= Im x <= 20, Re m > 0, Im m >= 0 and "
          "|m - 1| >= 1e-6; got x = "
       << x.real() << (x.imag() < 0 ? " - " : " + ") << std::abs(x.imag()) << "i, m = " << m.real()
       << (m.imag() < 0 ? " - " : " + ") << std::abs(m.imag()) << "i";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

ForwardAmplitude forward_amplitude(std::complex<double> x_in, std::complex<double> m_in) {
  check(x_in, m_in);
  const C x(x_in), m(m_in), mx = m * x;
  const R ax = std::abs(x);
  // Terms beyond n ≈ |x| + 4|x|^{1/3} fall off faster than geometrically; the
  // sum stops when two successive terms no longer change it (below), this is
  // only the length of the Dₙ tables, doubled if it was too short.
  std::size_t N = static_cast<std::size_t>(ax + 8 * std::cbrt(ax) + 24);
  thread_local std::vector<C> dx, dmx;
  for (;;) {
    log_derivatives(x, N, dx);
    log_derivatives(mx, N, dmx);
    const C inv_x = detail::recip(x);
    const C inv_m = detail::recip(m);
    const C i(0, 1);
    // ψ₀/ξ₀ = sin x / (−i e^{ix}) = i sin x e^{−ix};  ξ₁/ξ₀ = 1/x − i.
    C t = i * std::sin(x) * std::exp(-i * x);
    C q = inv_x - i;
    C sum(0);
    R magnitude = 0;
    int quiet = 0;
    for (std::size_t n = 1; n <= N; ++n) {
      if (n > 1) q = R(2 * n - 1) * inv_x - detail::recip(q);
      const C n_over_x = R(n) * inv_x;
      const C r_psi = dx[n] + n_over_x;  // ψ_{n−1}/ψₙ
      const C r_xi = detail::recip(q);   // ξ_{n−1}/ξₙ
      t = t * detail::recip(r_psi * q);  // ψₙ/ξₙ
      const C A = dmx[n] * inv_m + n_over_x;
      const C B = m * dmx[n] + n_over_x;
      // (recip: one real division instead of std::complex's scaled __divxc3;
      // nothing here comes near overflow, see lentz.hpp.)
      const C a = t * ((dmx[n] * inv_m - dx[n]) * detail::recip(A - r_xi));
      const C b = t * ((m * dmx[n] - dx[n]) * detail::recip(B - r_xi));
      const C term = R(2 * n + 1) * (a + b);
      sum += term;
      magnitude += R(2 * n + 1) * (std::sqrt(detail::norm2(a)) + std::sqrt(detail::norm2(b)));
      // Converged once past |x| and two terms in a row are below the last bit.
      const R eps = std::numeric_limits<R>::epsilon();
      if (R(n) > ax && detail::norm2(term) <= eps * eps * detail::norm2(sum)) {
        if (++quiet == 2) {
          ForwardAmplitude out;
          out.s0 = std::complex<double>(static_cast<double>(sum.real() / 2), static_cast<double>(sum.imag() / 2));
          out.magnitude = static_cast<double>(magnitude / 2);
          out.terms = n;
          return out;
        }
      } else {
        quiet = 0;
      }
    }
    N *= 2;  // the series had not converged within the table: longer tables
  }
}

}  // namespace attenuvis::mie
