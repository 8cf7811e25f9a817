// attenuvis::mie::spheres (attenuvis/mie/spheres.hpp): many spheres per call.
// The reference is sphere() itself, one sphere at a time.  Every lane of the
// vector path performs sphere()'s operations in sphere()'s order (the library
// is built without contraction), so the rounding bound of a lane against the
// single call is zero: results must be bit for bit equal, whichever
// instruction set the CPU selects and whichever thread evaluates them.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Bitwise equality of every field (a NaN equals the same NaN).
void check_equal(const mie::Efficiencies<double>& got, const mie::Efficiencies<double>& want) {
  CHECK(same_bits(got.qext, want.qext));
  CHECK(same_bits(got.qsca, want.qsca));
  CHECK(same_bits(got.qabs, want.qabs));
  CHECK(same_bits(got.qback, want.qback));
  CHECK(same_bits(got.qpr, want.qpr));
  CHECK(same_bits(got.g, want.g));
  CHECK(got.terms == want.terms);
}

std::vector<double> random_x(std::size_t count, double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  std::vector<double> x(count);
  for (double& v : x) v = std::exp(u(rng));
  return x;
}

}  // namespace

TEST_CASE("spheres(): one m, every batch size from 1 to 19 and 1001, equals sphere() bit for bit", "[mie][spheres]") {
  for (cd m : {cd(1.33, 1e-8), cd(1.5, 0.1), cd(10, 10), cd(1.0001, 0)}) {
    for (std::size_t count : {1u, 2u, 3u, 5u, 7u, 8u, 9u, 15u, 16u, 17u, 19u, 1001u}) {
      const auto x = random_x(count, 0.01, 300, static_cast<unsigned>(count));
      std::vector<mie::Efficiencies<double>> out(count);
      mie::SpheresOptions one_thread;
      one_thread.threads = 1;
      const auto errors = mie::spheres(x.data(), m, count, out.data(), one_thread);
      CHECK(errors.empty());
      for (std::size_t i = 0; i < count; ++i) {
        INFO("m = " << m << ", count " << count << ", x[" << i << "] = " << x[i]);
        check_equal(out[i], mie::sphere(x[i], m));
      }
    }
  }
}

TEST_CASE("spheres(): mixed indices, including spheres outside the vector path, and two threads", "[mie][spheres]") {
  // Outside the vector path: extended precision (|m - 1| < 5e-5, x > 1e4,
  // |m - 1| < 1e-2 with x > 1e3), D_n(mx) upward (k = 1000 at x = 2000).
  const std::vector<cd> ms = {{1.33, 1e-8}, {1.5, 0.1}, {10, 10}, {0.75, 0}, {1 + 1e-6, 0}, {1.0001, 1e-8},
                              {2, 1},       {1.5, 1000}, {0, 1.5}, {1.001, 0}};
  auto x = random_x(997, 1e-6, 2e3, 7);
  x.push_back(1.2e4);
  x.push_back(2e3);
  std::vector<cd> m(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) m[i] = ms[i % ms.size()];
  m[m.size() - 1] = cd(1.5, 1000);  // x = 2000: upward D_n(mx)
  for (unsigned threads : {1u, 2u}) {
    mie::SpheresOptions o;
    o.threads = threads;
    std::vector<mie::Efficiencies<double>> out(x.size());
    CHECK(mie::spheres(x.data(), m.data(), x.size(), out.data(), o).empty());
    for (std::size_t i = 0; i < x.size(); ++i) {
      INFO("threads " << threads << ", x[" << i << "] = " << x[i] << ", m = " << m[i]);
      check_equal(out[i], mie::sphere(x[i], m[i]));
    }
  }
}

TEST_CASE("spheres(): non-default options go through sphere() with those options", "[mie][spheres]") {
  const auto x = random_x(40, 0.1, 100, 3);
  mie::SpheresOptions o;
  o.options.terms = mie::TermRule::wiscombe;
  std::vector<mie::Efficiencies<double>> out(x.size());
  CHECK(mie::spheres(x.data(), cd(1.33, 1e-8), x.size(), out.data(), o).empty());
  for (std::size_t i = 0; i < x.size(); ++i) check_equal(out[i], mie::sphere(x[i], cd(1.33, 1e-8), o.options));
}

TEST_CASE("spheres(): extended_above keeps the vector path and equals sphere() with it, bit for bit", "[mie][spheres]") {
  // The bulk integrals ask for double recurrences up to x = 3e4 (weather's
  // mie_efficiencies); x from 1e-3 to 3e4 crosses the lanes and the range
  // (1e4, 3e4] that extended_above moves to double.
  const auto x = random_x(600, 1e-3, 3e4, 11);
  mie::SpheresOptions o;
  o.options.extended_above = 3e4;
  o.threads = 1;
  for (const cd m : {cd(1.33, 1e-8), cd(1.0001, 0), cd(1.5, 0.1)}) {
    std::vector<mie::Efficiencies<double>> out(x.size());
    CHECK(mie::spheres(x.data(), m, x.size(), out.data(), o).empty());
    for (std::size_t i = 0; i < x.size(); ++i) check_equal(out[i], mie::sphere(x[i], m, o.options));
  }
}

TEST_CASE("spheres(): bad elements are reported by index, the others computed", "[mie][spheres]") {
  std::vector<double> x = {1.0, 0.0, 2.0, NAN, 3.0, -1.0, 4.0, 5.0, 3e7, 6.0, 7.0};
  std::vector<cd> m(x.size(), cd(1.33, 1e-8));
  m[6] = cd(1.5, -0.1);  // k < 0
  m[9] = cd(-1.0, 0.0);  // n < 0
  std::vector<mie::Efficiencies<double>> out(x.size());
  const auto errors = mie::spheres(x.data(), m.data(), x.size(), out.data());
  REQUIRE(errors.size() == 6);
  const std::size_t bad[] = {1, 3, 5, 6, 8, 9};
  for (std::size_t k = 0; k < errors.size(); ++k) {
    CHECK(errors[k].index == bad[k]);
    CHECK_THAT(errors[k].message, Catch::Contains(k == 3 || k == 5 ? "refractive index" : "size parameter"));
    CHECK(std::isnan(out[bad[k]].qext));
  }
  for (std::size_t i : {0u, 2u, 4u, 7u, 10u}) check_equal(out[i], mie::sphere(x[i], m[i]));
}

TEST_CASE("spheres(): an empty batch does nothing", "[mie][spheres]") {
  CHECK(mie::spheres(nullptr, cd(1.33, 0), 0, nullptr).empty());
}

TEST_CASE("spheres(): every instruction set this CPU runs gives sphere()'s bits", "[mie][spheres]") {
  const auto sets = mie::spheres_instruction_sets();
  REQUIRE(!sets.empty());
  CHECK(sets.back() == "generic");
  // Mixed indices (δ and value slots, Lentz and Miller starts), x from 1e-3 to
  // 2e3, in an order the plan must rearrange (long and short series interleaved).
  const std::vector<cd> ms = {{1.33, 1e-8}, {1.5, 0.1}, {10, 10}, {1.0001, 0}, {1.05, 0.01}, {2, 1}};
  const auto x = random_x(203, 1e-3, 2e3, 11);
  std::vector<cd> m(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) m[i] = ms[(i * 7) % ms.size()];
  for (const auto& set : sets) {
    mie::SpheresOptions o;
    o.threads = 1;
    o.instruction_set = set;
    std::vector<mie::Efficiencies<double>> out(x.size());
    CHECK(mie::spheres(x.data(), m.data(), x.size(), out.data(), o).empty());
    for (std::size_t i = 0; i < x.size(); ++i) {
      INFO(set << ": x[" << i << "] = " << x[i] << ", m = " << m[i]);
      check_equal(out[i], mie::sphere(x[i], m[i]));
    }
  }
  mie::SpheresOptions unknown;
  unknown.instruction_set = "avx1024";
  mie::Efficiencies<double> q;
  const double one = 1.0;
  CHECK_THROWS_AS(mie::spheres(&one, cd(1.33, 0), 1, &q, unknown), std::invalid_argument);
}
