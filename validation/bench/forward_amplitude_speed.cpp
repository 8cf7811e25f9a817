// Benchmark of S(0) at complex size parameter (mie/forward_amplitude.hpp), the
// one Mie quantity the contour rules of sigma_ext evaluate: microseconds per
// point along a path panel of 32 points at height Im x = 4 (the contours'
// height) for |x| from 10^2 to 5 10^4, water at 550 nm (m = 1.333 +
// 1.96e-9i, Hale & Querry 1973), in double:
//   one   = forward_amplitude() point after point (one series at a time),
//   batch = forward_amplitudes() on the 32 points (series side by side),
// their ratio, and the accuracy side of the comparison: the largest
// |batch - one| over the sum of the two rounding bounds (<= 1: the same value
// within what each call reports as its rounding error), and the same against
// extended precision.  CPU seconds of this thread, best of three runs.
// Usage: forward_amplitude_speed
#include <algorithm>
#include <complex>
#include <cstdio>
#include <ctime>
#include <vector>

#include "attenuvis/mie/forward_amplitude.hpp"

namespace {

using attenuvis::mie::ForwardAmplitude;
using attenuvis::mie::Precision;

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Best of three of f(), in seconds.
template <class F>
double best_of_three(F&& f) {
  double best = 1e300;
  for (int r = 0; r < 3; ++r) {
    const double t0 = thread_seconds();
    f();
    best = std::min(best, thread_seconds() - t0);
  }
  return best;
}

// Largest |a - b| / (a's + b's rounding bounds).
double worst_ratio(const std::vector<ForwardAmplitude>& a, const std::vector<ForwardAmplitude>& b) {
  double worst = 0;
  for (std::size_t j = 0; j < a.size(); ++j)
    worst = std::max(worst, std::abs(a[j].s0 - b[j].s0) / (a[j].rounding_bound() + b[j].rounding_bound()));
  return worst;
}

}  // namespace

int main() {
  const std::complex<double> m(1.333, 1.96e-9);
  const int count = 32;
  std::printf("S(0) at x = t + 4i, %d points 0.37 apart in t, m = 1.333 + 1.96e-9i, double; CPU of one thread, best "
              "of 3\n",
              count);
  std::printf("%8s %12s %12s %8s %16s %16s\n", "|x|", "one [us]", "batch [us]", "one/bat", "|bat-one|/bound",
              "|bat-ext|/bound");
  for (double t0 : {1e2, 1e3, 1e4, 3e4, 5e4}) {
    std::vector<std::complex<double>> x(count);
    for (int j = 0; j < count; ++j) x[j] = {t0 + 0.37 * j, 4.0};
    std::vector<ForwardAmplitude> one(count), batch(count), extended(count);
    const double s_one = best_of_three([&] {
      for (int j = 0; j < count; ++j) one[j] = attenuvis::mie::forward_amplitude(x[j], m, Precision::double_precision);
    });
    const double s_batch = best_of_three([&] {
      attenuvis::mie::forward_amplitudes(x.data(), count, m, Precision::double_precision, batch.data());
    });
    attenuvis::mie::forward_amplitudes(x.data(), count, m, Precision::extended, extended.data());
    std::printf("%8.0f %12.2f %12.2f %8.2f %16.3f %16.3f\n", t0, 1e6 * s_one / count, 1e6 * s_batch / count,
                s_one / s_batch, worst_ratio(batch, one), worst_ratio(batch, extended));
    std::fflush(stdout);
  }
  return 0;
}
