// The vectorised contrast kernel (visgraph/src/contrast_kernel.cpp, internal)
// against an independent reference: C = expl(-sigma d) in long double (64-bit
// significand, glibc's expl accurate to about 1 ulp of long double, i.e.
// ~1e-19 relative), scaled to the kernel's fixed point 2^-40 and rounded.
// The kernel's own exp is claimed to ~2 ulp of double (4.4e-16 relative), so
// its fixed-point value may differ from the reference's rounding only when
// the exact value lies within 4.4e-16 * 2^40 < 5e-4 units of a rounding
// boundary: the test allows a difference of one unit there and nowhere else.
#include <catch2/catch.hpp>

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace vd = attenuvis::visgraph::detail;

TEST_CASE("contrast kernel matches expl in fixed point", "[visgraph][kernel]") {
  std::mt19937_64 rng(17);
  const auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  constexpr int L = vd::kLanes;
  const std::vector<double> neg_sigma = {-0.0, -0.00015, -0.0045, -0.02874311, -0.0374, -1.0, -37.0};
  const int K = static_cast<int>(neg_sigma.size());
  std::vector<std::int64_t> c(static_cast<std::size_t>(K) * L);
  std::int64_t d_fixed[L];
  double distance[L], visible[L];
  std::size_t checked = 0, off_by_one = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    for (int l = 0; l < L; ++l) {
      // Distances from 1 mm to 20 km, log-uniform; every 5th lane invisible.
      distance[l] = 1e-3 * std::pow(2e7, unit());
      visible[l] = (trial * L + l) % 5 == 0 ? 0.0 : 1.0;
    }
    vd::contrast_lanes(distance, visible, neg_sigma.data(), K, c.data(), d_fixed);
    for (int l = 0; l < L; ++l) {
      const long double d_ref = static_cast<long double>(distance[l]) * vd::kDistanceScale;
      CHECK(d_fixed[l] == (visible[l] != 0 ? std::llrint(d_ref) : 0));
      for (int k = 0; k < K; ++k) {
        const std::int64_t got = c[static_cast<std::size_t>(k) * L + l];
        if (visible[l] == 0) {
          CHECK(got == 0);
          continue;
        }
        const long double exact =
            std::exp(static_cast<long double>(neg_sigma[k]) * distance[l]) * vd::kContrastScale;
        const std::int64_t want = std::llrint(exact);
        const long double to_boundary = std::abs(exact - std::floor(exact) - 0.5L);
        ++checked;
        if (got != want) {
          ++off_by_one;
          INFO("sigma " << -neg_sigma[k] << " d " << distance[l] << " exact " << static_cast<double>(exact));
          CHECK(std::abs(got - want) == 1);
          CHECK(to_boundary < 5e-4L);
        }
      }
    }
  }
  CHECK(checked > 200000);
  CHECK(off_by_one < checked / 1000);  // boundary cases are rare (fraction ~1e-3 of the window)
}

TEST_CASE("contrast kernel: sigma d beyond 700 gives zero, sigma 0 gives one", "[visgraph][kernel]") {
  constexpr int L = vd::kLanes;
  double distance[L], visible[L];
  for (int l = 0; l < L; ++l) distance[l] = 1000.0 * (l + 1), visible[l] = 1.0;
  const double neg_sigma[2] = {-1.0, 0.0};
  std::int64_t c[2 * L], d_fixed[L];
  vd::contrast_lanes(distance, visible, neg_sigma, 2, c, d_fixed);
  for (int l = 0; l < L; ++l) {
    CHECK(c[l] == 0);                              // exp(-1000 ...) * 2^40 rounds to 0
    CHECK(c[L + l] == std::int64_t{1} << 40);      // exp(0) = 1 exactly
  }
}

// The instruction-set variants (baseline, AVX2, AVX-512 intrinsics) run the
// same operations in the same order, so they must agree to the bit; the
// baseline variant is the one checked against expl above on every CPU.
TEST_CASE("contrast kernel: every instruction set gives the same bits", "[visgraph][kernel]") {
  std::mt19937_64 rng(31);
  const auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  constexpr int L = vd::kLanes;
  // Sigma 0, the seed paper's four, steep ones that reach the -700 clamp,
  // and K = 11 (more than one block of four).
  const std::vector<double> neg_sigma = {-0.0, -1.5e-4, -0.0045, -0.02874311, -0.0374, -1.0, -37.0,
                                         -0.3,  -2e-3,   -1e-6,   -9.0};
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    double distance[L], visible[L];
    for (int l = 0; l < L; ++l) {
      // 0, 1 mm to 20 km log-uniform, and exactly where sigma d = 700.
      distance[l] = l == 0 ? 0.0 : l == 1 ? 700.0 / 37.0 : 1e-3 * std::pow(2e7, unit());
      visible[l] = rng() % 4 == 0 ? 0.0 : 1.0;
    }
    const int K = 1 + trial % static_cast<int>(neg_sigma.size());
    std::vector<std::int64_t> want_c(static_cast<std::size_t>(K) * L), want_d(L);
    REQUIRE(vd::contrast_lanes_with(0, distance, visible, neg_sigma.data(), K, want_c.data(), want_d.data()));
    for (int isa = 1; isa < 3; ++isa) {
      std::vector<std::int64_t> c(want_c.size(), -1), d(L, -1);
      if (!vd::contrast_lanes_with(isa, distance, visible, neg_sigma.data(), K, c.data(), d.data())) continue;
      INFO("trial " << trial << ", instruction set " << isa << ", K " << K);
      CHECK(c == want_c);
      CHECK(d == want_d);
      ++compared;
    }
  }
  // Both wider variants where the CPU has them; none on one without AVX2.
  INFO("variants compared: " << compared);
  CHECK(compared % 3000 == 0);
}
