// The scoring floor of the visibility-graph benchmarks
// (visgraph_benchmark.hpp): a plain loop over every unordered pair,
// distance, exp(-sigma_k d) and double sums to both ends, as a compiler
// makes of it with -ffast-math (this file only: CMakeLists.txt), which lets
// GCC call glibc's vector exp (libmvec) and reorder the sums.  No policy,
// no fixed point, no rays: the least work that produces the same kind of
// numbers, for the engine's in-sight scoring to be measured against.
#include <attenuvis/validation/visgraph_benchmark.hpp>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace attenuvis::validation {

namespace {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define ATTENUVIS_FLOOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_FLOOR_CLONES
#endif

struct Coordinates {
  const double *x, *y, *z;
  std::size_t n;
};

// Row i against every j > i for one sigma (sums s0) or four (s0..s3): the
// accumulators are separate restrict pointers, so that GCC vectorises the
// loop over j, exp included.
ATTENUVIS_FLOOR_CLONES
void floor_row_1(const double* __restrict x, const double* __restrict y, const double* __restrict z, std::size_t i,
                 std::size_t n, double a0, double* __restrict s0) {
  double r0 = 0;
  const double ox = x[i], oy = y[i], oz = z[i];
  for (std::size_t j = i + 1; j < n; ++j) {
    const double dx = x[j] - ox, dy = y[j] - oy, dz = z[j] - oz;
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double c0 = std::exp(a0 * d);
    r0 += c0;
    s0[j] += c0;
  }
  s0[i] += r0;
}

ATTENUVIS_FLOOR_CLONES
void floor_row_4(const double* __restrict x, const double* __restrict y, const double* __restrict z, std::size_t i,
                 std::size_t n, const double* a, double* __restrict s0, double* __restrict s1, double* __restrict s2,
                 double* __restrict s3) {
  double r0 = 0, r1 = 0, r2 = 0, r3 = 0;
  const double ox = x[i], oy = y[i], oz = z[i];
  const double a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3];
  for (std::size_t j = i + 1; j < n; ++j) {
    const double dx = x[j] - ox, dy = y[j] - oy, dz = z[j] - oz;
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double c0 = std::exp(a0 * d), c1 = std::exp(a1 * d), c2 = std::exp(a2 * d), c3 = std::exp(a3 * d);
    r0 += c0, r1 += c1, r2 += c2, r3 += c3;
    s0[j] += c0, s1[j] += c1, s2[j] += c2, s3[j] += c3;
  }
  s0[i] += r0, s1[i] += r1, s2[i] += r2, s3[i] += r3;
}

// Row i for every sigma: groups of four, then one at a time.
void floor_row(const Coordinates& c, std::size_t i, const std::vector<double>& neg_sigma, std::vector<double>& sums) {
  const std::size_t K = neg_sigma.size(), n = c.n;
  std::size_t k = 0;
  for (; k + 4 <= K; k += 4)
    floor_row_4(c.x, c.y, c.z, i, n, neg_sigma.data() + k, sums.data() + k * n, sums.data() + (k + 1) * n,
                sums.data() + (k + 2) * n, sums.data() + (k + 3) * n);
  for (; k < K; ++k) floor_row_1(c.x, c.y, c.z, i, n, neg_sigma[k], sums.data() + k * n);
}
}  // namespace

double raw_scoring_loop(const std::vector<Eigen::Vector3d>& eyes, const std::vector<double>& sigmas, int threads) {
  const std::size_t n = eyes.size();
  std::vector<double> x(n), y(n), z(n), neg_sigma;
  for (std::size_t i = 0; i < n; ++i) x[i] = eyes[i].x(), y[i] = eyes[i].y(), z[i] = eyes[i].z();
  for (double s : sigmas) neg_sigma.push_back(-s);
  const Coordinates c{x.data(), y.data(), z.data(), n};
  tbb::enumerable_thread_specific<std::vector<double>> sums([&] { return std::vector<double>(sigmas.size() * n, 0.0); });
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    // Rows in chunks from both ends of the triangle, so that chunks cost alike.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (n + 1) / 2, 16), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<double>& s = sums.local();
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        floor_row(c, i, neg_sigma, s);
        if (n - 1 - i != i) floor_row(c, n - 1 - i, neg_sigma, s);
      }
    });
  });
  double total = 0;
  for (const std::vector<double>& s : sums)
    for (double v : s) total += v;
  return total;
}

}  // namespace attenuvis::validation
