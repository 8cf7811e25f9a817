// Error against run time of the phase-function moments χ_0..χ_2N of one sphere
// (attenuvis/mie/legendre_moments.hpp), and of the full scattering-matrix
// expansion, with the cost of the efficiencies measured in the same run as the
// baseline.  For x in {1, 10, 100, 1000} (or the --x list) and m in {1.0001,
// 1.33 + 1e-8i, 1.5 + 0.1i, 10 + 10i}, one core:
//   eff        mie::sphere(x, m)
//   coeff      mie::scatter(x, m, {coefficients = true}) — what the moments start from
//   mom        mie::phase_function_moments on those coefficients, rule cached (the
//              node loops in the clone for this CPU's instruction set)
//   portable   the same kernels compiled here for baseline x86-64 (SSE2): the
//              speed-up of the per-instruction-set clones, and a check that both
//              give the same bits
//   rule       building the Gauss–Legendre rule of 2N+1 nodes (once per order bin
//              and thread; mie::gauss_legendre_half_rule, uncached)
//   expan      mie::scattering_matrix_expansion (α1..α4, β1, β2, l = 0..2N)
//   max|err|   max over l of |χ_l − reference|, the reference being the same
//              algorithm in x87 extended precision on the 50-digit referee's Mie
//              coefficients (within 7e-19 of the 50-digit moments for x <= 1000,
//              tests/mie/test_legendre_moments.cpp): the error of the whole double
//              path, coefficients included.
// mom/eff = (coeff + mom)/eff.  Times: median of 7 batches, each >= 50 ms.
//
// Usage: mie_moments_speed [--x X[,X...]]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/detail/legendre_moments_impl.hpp"
#include "attenuvis/mie/legendre_moments_referee.hpp"

namespace {

namespace mie = attenuvis::mie;
volatile double g_sink = 0;

template <class F>
double median_seconds(F&& f, int batches_wanted = 7, double batch_s = 0.05) {
  using clock = std::chrono::steady_clock;
  std::vector<double> batches;
  for (int b = 0; b < batches_wanted; ++b) {
    int reps = 0;
    const auto t0 = clock::now();
    double elapsed = 0;
    do {
      f();
      ++reps;
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < batch_s);
    batches.push_back(elapsed / reps);
  }
  std::nth_element(batches.begin(), batches.begin() + batches.size() / 2, batches.end());
  return batches[batches.size() / 2];
}

// χ_l in x87 extended precision from the 50-digit referee's coefficients.
std::vector<long double> extended_reference(double x, std::complex<double> m) {
  mie::Extras ex;
  ex.coefficients = true;
  const auto rs = mie::scatter_referee(mie::Referee(x),
                                       mie::Complex<mie::Referee>(mie::Referee(m.real()), mie::Referee(m.imag())), ex);
  std::vector<std::complex<long double>> a(rs.a.size()), b(rs.b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = {rs.a[i].real().convert_to<long double>(), rs.a[i].imag().convert_to<long double>()};
    b[i] = {rs.b[i].real().convert_to<long double>(), rs.b[i].imag().convert_to<long double>()};
  }
  return mie::detail::legendre_moments<long double>(a, b, mie::all_orders);
}

double max_abs_error(const std::vector<double>& d, const std::vector<long double>& r) {
  long double worst = 0;
  for (std::size_t l = 0; l < std::max(d.size(), r.size()); ++l) {
    const long double dv = l < d.size() ? d[l] : 0.0L, rv = l < r.size() ? r[l] : 0.0L;
    worst = std::max(worst, std::abs(dv - rv));
  }
  return static_cast<double>(worst);
}

std::vector<double> parse_list(const std::string& text) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<double> xs = {1.0, 10.0, 100.0, 1000.0};
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--x" && i + 1 < argc) {
        xs = parse_list(argv[++i]);
      } else {
        std::fprintf(stderr, "mie_moments_speed: unknown argument %s\nusage: mie_moments_speed [--x X[,X...]]\n",
                     a.c_str());
        return 2;
      }
    }
    const std::vector<std::complex<double>> ms = {{1.0001, 0}, {1.33, 1e-8}, {1.5, 0.1}, {10, 10}};
    std::printf("Phase-function moments chi_0..chi_2N and scattering-matrix expansion of one sphere (one core)\n");
    std::printf("%7s %-12s %6s %9s %9s %10s %10s %8s %10s %11s %8s %8s %9s\n", "x", "m", "N", "eff[us]", "coeff[us]",
                "mom[us]", "port.[us]", "port/mom", "rule[us]", "expan[us]", "mom/eff", "exp/eff", "max|err|");
    for (const double x : xs)
      for (const auto m : ms) {
        mie::Extras ex;
        ex.coefficients = true;
        const auto s = mie::scatter(x, m, ex);
        const std::size_t order = 2 * s.a.size() + 1;
        const double t_eff = median_seconds([&] { g_sink = g_sink + mie::sphere(x, m).qext; });
        const double t_coef = median_seconds([&] { g_sink = g_sink + mie::scatter(x, m, ex).q.qext; });
        const std::vector<double> chi = mie::phase_function_moments(s);
        const std::vector<double> chi_portable = mie::detail::legendre_moments<double, false>(s.a, s.b, mie::all_orders);
        if (chi != chi_portable) throw std::runtime_error("per-instruction-set moments differ from the portable build");
        const double t_mom = median_seconds([&] { g_sink = g_sink + mie::phase_function_moments(s)[1]; });
        const double t_port = median_seconds(
            [&] { g_sink = g_sink + mie::detail::legendre_moments<double, false>(s.a, s.b, mie::all_orders)[1]; });
        std::vector<double> theta, weight;
        const double t_rule = median_seconds([&] { mie::gauss_legendre_half_rule(order, theta, weight); }, 3);
        const double t_exp =
            median_seconds([&] { g_sink = g_sink + mie::scattering_matrix_expansion(s).alpha1[1]; }, 3);
        const double err = max_abs_error(chi, extended_reference(x, m));
        char label[32];
        std::snprintf(label, sizeof label, "%g%+gi", m.real(), m.imag());
        std::printf("%7g %-12s %6zu %9.2f %9.2f %10.1f %10.1f %8.2f %10.0f %11.0f %8.1f %8.1f %9.1e\n", x, label,
                    s.a.size(), t_eff * 1e6, t_coef * 1e6, t_mom * 1e6, t_port * 1e6, t_port / t_mom, t_rule * 1e6,
                    t_exp * 1e6, (t_coef + t_mom) / t_eff, (t_coef + t_exp) / t_eff, err);
      }
    std::printf("\nmom/eff = (coeff + mom)/eff: the moments cost O(N^2) (2N+1 quadrature nodes x N terms, "
                "2N+1 degrees x N+1 nodes), the efficiencies O(N).\nport/mom: baseline x86-64 build of the "
                "same node loops against the clone this CPU runs (same bits, checked).\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mie_moments_speed: error: %s\n", e.what());
    return 1;
  }
}
