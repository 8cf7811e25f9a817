// Blocks of pairs in sight (detail/visible_block.hpp, the culled pass's
// kernel) against the packet path they replace, bit for bit: each pair's
// distance as build_packet computes it, its contrast ratios and distance in
// fixed point from contrast_lanes (the packet kernel, itself checked against
// expl in test_contrast_kernel.cpp), summed per node.  Every instruction set
// this CPU runs is compared (the AVX-512 variant is written with
// intrinsics, the others are the compiler's loops).
#if defined(__clang__)
#pragma clang fp contract(off)
#else
#pragma GCC optimize("fp-contract=off")
#endif

#include <catch2/catch.hpp>

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>
#include <attenuvis/visgraph/detail/visible_block.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace vd = attenuvis::visgraph::detail;

namespace {
constexpr int L = vd::kLanes;

struct Expected {
  std::vector<std::int64_t> acc;
  std::vector<double> max_distance;
  std::uint64_t visible = 0, coincident = 0;
};

// The packet path, pair by pair: build_packet's distance and policy
// (coincident below 1e-6 m, nothing beyond max_distance), contrast_lanes'
// fixed point.
Expected by_pairs(const vd::BlockSide& rows, const vd::BlockSide& cols, bool same, const std::vector<double>& neg_sigma,
                  double max_distance, std::size_t N) {
  const int K = static_cast<int>(neg_sigma.size());
  Expected e;
  e.acc.assign((2 + static_cast<std::size_t>(K)) * N, 0);
  e.max_distance.assign(N, 0.0);
  for (int a = 0; a < rows.count; ++a)
    for (int b = same ? a + 1 : 0; b < cols.count; ++b) {
      const std::size_t i = rows.first + static_cast<std::size_t>(a), j = cols.first + static_cast<std::size_t>(b);
      const double dx = cols.x[j] - rows.x[i], dy = cols.y[j] - rows.y[i], dz = cols.z[j] - rows.z[i];
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (d < 1e-6) {
        ++e.coincident;
        continue;
      }
      if (!(d <= max_distance)) continue;
      ++e.visible;
      double distance[L] = {d}, visible[L] = {1.0};
      std::vector<std::int64_t> c(static_cast<std::size_t>(std::max(K, 1)) * L);
      std::int64_t d_fixed[L];
      vd::contrast_lanes(distance, visible, neg_sigma.data(), K, c.data(), d_fixed);
      for (std::size_t node : {i, j}) {
        e.acc[node] += 1;
        e.acc[N + node] += d_fixed[0];
        for (int k = 0; k < K; ++k) e.acc[static_cast<std::size_t>(2 + k) * N + node] += c[static_cast<std::size_t>(k) * L];
        e.max_distance[node] = std::max(e.max_distance[node], d);
      }
    }
  return e;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
}  // namespace

TEST_CASE("visible blocks: every instruction set gives the packets' bits", "[visgraph][kernel]") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> coordinate(-300.0, 300.0);
  const std::vector<std::vector<double>> sigma_sets = {
      {}, {-1.5e-4}, {-0.0, -1.5e-4, -0.0045, -0.02874311}, {-0.0374, -1.0, -37.0, -0.3, -2e-3, -1e-6, -0.5, -4.0, -0.0, -9.0, -0.1}};
  int compared = 0;
  for (int trial = 0; trial < 60; ++trial) {
    // Two leaves of up to 16 nodes in one coordinate array; some nodes
    // repeated (coincident pairs), some far apart (sigma d beyond 700).
    // Columns: a leaf, or (every 4th trial) a run of up to 600 nodes.
    const int na = 1 + static_cast<int>(rng() % 16);
    const int nb = trial % 4 == 3 ? 17 + static_cast<int>(rng() % 600) : 1 + static_cast<int>(rng() % 16);
    const std::size_t N = static_cast<std::size_t>(na + nb) + 3;
    std::vector<double> x(N), y(N), z(N);
    for (std::size_t n = 0; n < N; ++n) x[n] = coordinate(rng), y[n] = coordinate(rng), z[n] = coordinate(rng) / 30;
    for (int r = 0; r < 3; ++r) {
      const std::size_t from = rng() % N, to = rng() % N;
      x[to] = x[from], y[to] = y[from], z[to] = z[from] + (r == 2 ? 5e-7 : 0.0);
    }
    const bool same = trial % 3 == 0 && nb <= 16;
    const vd::BlockSide rows{x.data(), y.data(), z.data(), 1, na};
    const vd::BlockSide cols = same ? rows : vd::BlockSide{x.data(), y.data(), z.data(), 1 + static_cast<std::size_t>(na), nb};
    const std::vector<double>& neg_sigma = sigma_sets[static_cast<std::size_t>(trial) % sigma_sets.size()];
    const double max_distance = trial % 4 == 1 ? 250.0 : std::numeric_limits<double>::infinity();
    Expected want = by_pairs(rows, cols, same, neg_sigma, max_distance, N);
    // Without distance statistics the distance slot is left alone.
    const bool distances = trial % 5 != 2;
    if (!distances) std::fill(want.acc.begin() + static_cast<std::ptrdiff_t>(N), want.acc.begin() + static_cast<std::ptrdiff_t>(2 * N), 0);
    for (int isa = 0; isa < 3; ++isa) {
      std::vector<std::int64_t> acc(want.acc.size(), 0);
      std::vector<double> max_distance_of(N, 0.0);
      vd::BlockCounts counts;
      if (!vd::score_visible_block_with(isa, rows, cols, same, neg_sigma.data(), static_cast<int>(neg_sigma.size()),
                                        max_distance, acc.data(), N, distances ? max_distance_of.data() : nullptr,
                                        counts))
        continue;
      INFO("trial " << trial << ", instruction set " << isa << ", K " << neg_sigma.size());
      CHECK(acc == want.acc);
      if (distances) CHECK(same_bits(max_distance_of, want.max_distance));
      CHECK(counts.visible == want.visible);
      CHECK(counts.coincident == want.coincident);
      ++compared;
    }
  }
  CHECK(compared >= 60);  // at least the baseline variant everywhere
}
