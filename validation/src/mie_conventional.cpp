// The conventional (textbook) Lorenz–Mie baseline; see mie_conventional.hpp.
// Written from the equations of Bohren & Huffman (1983), ch. 4:
//   a_n = [(D_n/m + n/x) psi_n - psi_{n-1}] / [(D_n/m + n/x) xi_n - xi_{n-1}]   (4.88)
//   b_n = [(m D_n + n/x) psi_n - psi_{n-1}] / [(m D_n + n/x) xi_n - xi_{n-1}]
//   D_{n-1} = n/(mx) - 1 / (D_n + n/(mx))                                        (4.89)
//   Qext = 2/x^2 sum (2n+1) Re(a_n + b_n),  Qsca = 2/x^2 sum (2n+1)(|a_n|^2+|b_n|^2)
//   g Qsca = 4/x^2 sum [ n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1})
//                        + (2n+1)/(n(n+1)) Re(a_n b*_n) ]                        (4.  p. 120)
//   Qback = |sum (2n+1)(-1)^n (a_n - b_n)|^2 / x^2
// with the Riccati–Bessel functions psi_n = x j_n(x), chi_n = -x y_n(x) by upward
// recurrence r_{n} = (2n-1)/x r_{n-1} - r_{n-2} and xi_n = psi_n - i chi_n.
#include "attenuvis/validation/mie_conventional.hpp"

#include <cmath>
#include <vector>

namespace attenuvis::validation {

int wiscombe_term_count(double x) {
  return static_cast<int>(x + 4.05 * std::cbrt(x) + 2.0);
}

ConventionalMieResult conventional_bhmie(double x, std::complex<double> m) {
  using cd = std::complex<double>;
  ConventionalMieResult r;
  const int N = wiscombe_term_count(x);
  r.terms = N;
  const cd mx = m * x;
  // Downward recurrence for D_n(mx) from zero at nmx = max(N, |mx|) + 15.
  // Only D_1..D_N are used, so values above N are not stored.
  const int nmx = static_cast<int>(std::max<double>(N, std::abs(mx)) + 15.0);
  std::vector<cd> D(static_cast<size_t>(N) + 1);
  cd d(0.0, 0.0);
  for (int n = nmx; n >= 2; --n) {
    const cd n_over_mx = static_cast<double>(n) / mx;
    d = n_over_mx - 1.0 / (d + n_over_mx);  // this is D_{n-1}
    if (n - 1 <= N) D[static_cast<size_t>(n - 1)] = d;
  }

  double psi0 = std::cos(x), psi1 = std::sin(x);  // psi_{-1}, psi_0
  double chi0 = -std::sin(x), chi1 = std::cos(x);  // chi_{-1}, chi_0
  cd xi1(psi1, -chi1);
  double sum_ext = 0, sum_sca = 0, sum_g = 0;
  cd sum_back(0, 0), a_prev(0, 0), b_prev(0, 0);
  for (int n = 1; n <= N; ++n) {
    const double dn = n;
    const double psi = (2 * dn - 1) / x * psi1 - psi0;
    const double chi = (2 * dn - 1) / x * chi1 - chi0;
    const cd xi(psi, -chi);
    const cd Dn = D[static_cast<size_t>(n)];
    const cd ta = Dn / m + dn / x;
    const cd tb = m * Dn + dn / x;
    const cd a = (ta * psi - psi1) / (ta * xi - xi1);
    const cd b = (tb * psi - psi1) / (tb * xi - xi1);
    sum_ext += (2 * dn + 1) * (a.real() + b.real());
    sum_sca += (2 * dn + 1) * (std::norm(a) + std::norm(b));
    sum_back += (2 * dn + 1) * ((n % 2) ? -1.0 : 1.0) * (a - b);
    sum_g += (2 * dn + 1) / (dn * (dn + 1)) * (a.real() * b.real() + a.imag() * b.imag());
    if (n > 1) {
      const double w = (dn - 1) * (dn + 1) / dn;  // n(n+2)/(n+1) for the previous n
      sum_g += w * (a_prev.real() * a.real() + a_prev.imag() * a.imag() +
                    b_prev.real() * b.real() + b_prev.imag() * b.imag());
    }
    a_prev = a;
    b_prev = b;
    psi0 = psi1;
    psi1 = psi;
    chi0 = chi1;
    chi1 = chi;
    xi1 = cd(psi1, -chi1);
  }
  const double x2 = x * x;
  r.qext = 2.0 / x2 * sum_ext;
  r.qsca = 2.0 / x2 * sum_sca;
  r.qabs = r.qext - r.qsca;
  r.qback = std::norm(sum_back) / x2;
  r.g = 4.0 / x2 * sum_g / r.qsca;
  return r;
}

}  // namespace attenuvis::validation
