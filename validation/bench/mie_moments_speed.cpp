// Cost of the phase-function moments and of the full scattering-matrix expansion
// of one sphere, as a ratio to the cost of its efficiencies measured in the same
// run.  At x = 1000 and m in {1.0001, 1.33 + 1e-8i, 1.5 + 0.1i, 10 + 10i}:
//   efficiencies   mie::sphere(x, m)
//   coefficients   mie::scatter(x, m, {coefficients = true})
//   moments        mie::phase_function_moments (χ_l, l = 0..2N) on those coefficients,
//                  Gauss–Legendre rule cached (a second sphere of similar N)
//   moments cold   the same with the rule built first (the first sphere of a run, or
//                  one whose N differs by more than ~6% from the previous one)
//   expansion      mie::scattering_matrix_expansion (α1..α4, β1, β2, l = 0..2N)
// Ratio columns: (coefficients + moments) / efficiencies, and the same for the
// expansion.  Median of 7 batches, each batch repeated to >= 50 ms.
//
// Usage: mie_moments_speed [--x X]
#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/legendre_moments.hpp"

namespace {

namespace mie = attenuvis::mie;
volatile double g_sink = 0;

template <class F>
double median_seconds(F&& f) {
  using clock = std::chrono::steady_clock;
  std::vector<double> batches;
  for (int b = 0; b < 7; ++b) {
    int reps = 0;
    const auto t0 = clock::now();
    double elapsed = 0;
    do {
      f();
      ++reps;
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < 0.05);
    batches.push_back(elapsed / reps);
  }
  std::nth_element(batches.begin(), batches.begin() + 3, batches.end());
  return batches[3];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    double x = 1000.0;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--x" && i + 1 < argc) {
        x = std::stod(argv[++i]);
      } else {
        std::fprintf(stderr, "mie_moments_speed: unknown argument %s\nusage: mie_moments_speed [--x X]\n",
                     a.c_str());
        return 2;
      }
    }
    const std::vector<std::complex<double>> ms = {{1.0001, 0}, {1.33, 1e-8}, {1.5, 0.1}, {10, 10}};
    std::printf("Phase-function moments and scattering-matrix expansion of one sphere, x = %g (one core)\n", x);
    std::printf("%-14s %6s %12s %12s %12s %12s %12s %10s %10s\n", "m", "N", "eff [us]", "coeff [us]",
                "mom [us]", "mom cold[us]", "expan [us]", "mom/eff", "expan/eff");
    for (const auto m : ms) {
      mie::Extras ex;
      ex.coefficients = true;
      const auto s = mie::scatter(x, m, ex);
      const double t_eff = median_seconds([&] { g_sink = g_sink + mie::sphere(x, m).qext; });
      const double t_coef = median_seconds([&] { g_sink = g_sink + mie::scatter(x, m, ex).q.qext; });
      const double t_mom = median_seconds([&] { g_sink = g_sink + mie::phase_function_moments(s)[1]; });
      // Cold: alternate with a small sphere (N ~ 5), whose call leaves a rule too
      // small for s in the cache, so s's rule of 2N+1 nodes is rebuilt every time.
      const auto small = mie::scatter(0.5, m, ex);
      const double t_pair = median_seconds([&] {
        g_sink = g_sink + mie::phase_function_moments(small)[0] + mie::phase_function_moments(s)[1];
      });
      const double t_small = median_seconds([&] { g_sink = g_sink + mie::phase_function_moments(small)[0]; });
      const double t_cold = t_pair - t_small;
      const double t_exp = median_seconds([&] { g_sink = g_sink + mie::scattering_matrix_expansion(s).alpha1[1]; });
      char label[32];
      std::snprintf(label, sizeof label, "%g%+gi", m.real(), m.imag());
      std::printf("%-14s %6zu %12.1f %12.1f %12.1f %12.1f %12.1f %10.1f %10.1f\n", label, s.a.size(), t_eff * 1e6,
                  t_coef * 1e6, t_mom * 1e6, t_cold * 1e6, t_exp * 1e6, (t_coef + t_mom) / t_eff,
                  (t_coef + t_exp) / t_eff);
    }
    std::printf("\nmom/eff = (coefficients + moments, rule cached) / efficiencies; the moments cost O(N^2) "
                "(2N+1 quadrature nodes x N terms), the efficiencies O(N).\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mie_moments_speed: error: %s\n", e.what());
    return 1;
  }
}
