// Properties every answer in the documented domain (mie.hpp) must have, over
// random inputs: finite efficiencies, energy balance Qext = Qsca + Qabs
// (B&H 4.61-4.62 with Qabs from its own sum), 0 <= albedo <= 1, |g| <= 1
// (g = <cos theta>, B&H 4.74), Qback >= 0, and many spheres at once equal to
// one at a time.  No reference numbers: the identities are the reference.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"

namespace mie = attenuvis::mie;

namespace {

struct Draw {
  double x;
  std::complex<double> m;
};

// x log-uniform in [1e-3, 3e3]; n uniform in [0.5, 10]; k zero a quarter of the
// time, else log-uniform in [1e-9, 1e3].
std::vector<Draw> draws(std::size_t count) {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Draw> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double x = std::pow(10.0, -3.0 + u(rng) * std::log10(3e6));
    const double n = 0.5 + 9.5 * u(rng);
    const double k = u(rng) < 0.25 ? 0.0 : std::pow(10.0, -9.0 + 12.0 * u(rng));
    out.push_back({x, {n, k}});
  }
  return out;
}

}  // namespace

TEST_CASE("random spheres in the domain: finite, energy balance, albedo and g in range", "[mie][properties]") {
  for (const Draw& d : draws(3000)) {
    const auto q = mie::sphere(d.x, d.m);
    INFO("x = " << d.x << ", m = " << d.m);
    REQUIRE(std::isfinite(q.qext));
    REQUIRE(std::isfinite(q.qsca));
    REQUIRE(std::isfinite(q.qabs));
    REQUIRE(std::isfinite(q.qback));
    REQUIRE(std::isfinite(q.g));
    CHECK(q.qsca >= 0);
    CHECK(q.qabs >= 0);
    CHECK(q.qback >= 0);
    // Qext, Qsca and Qabs are three sums; each is within ~1e-13 of its exact value.
    CHECK(std::abs(q.qext - q.qsca - q.qabs) <= 1e-12 * q.qext);
    CHECK(q.qsca <= q.qext * (1 + 1e-12));
    CHECK(std::abs(q.g) <= 1.0);
    if (d.m.imag() == 0) CHECK(q.qabs == 0);
  }
}

TEST_CASE("random spheres: many at once equal one at a time", "[mie][properties]") {
  const auto ds = draws(257);  // an odd count: the last vector block is partly filled
  std::vector<double> x;
  std::vector<std::complex<double>> m;
  for (const Draw& d : ds) x.push_back(d.x), m.push_back(d.m);
  std::vector<mie::Efficiencies<double>> many(ds.size());
  REQUIRE(mie::spheres(x.data(), m.data(), ds.size(), many.data()).empty());
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const auto one = mie::sphere(ds[i].x, ds[i].m);
    INFO("element " << i << ": x = " << ds[i].x << ", m = " << ds[i].m);
    CHECK(many[i].qext == one.qext);
    CHECK(many[i].qback == one.qback);
    CHECK(many[i].g == one.g);
  }
}
