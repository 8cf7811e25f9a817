// layered_sphere() (attenuvis/mie/layered.hpp): the identities that tie it to
// the homogeneous sphere, the angular machinery on its coefficients, the
// perfectly conducting core, and its argument checks.  Accuracy against the
// 50-digit referee is test_layered_referee.cpp; published and peer values
// test_layered_published.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <cstring>
#include <iomanip>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/layered_referee.hpp"
#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/scattering_matrix.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two evaluations of the same sphere by different algorithms, each within
// ~1e-13 of the exact value on its stress grid (the referee tests), must
// agree within a few times that: 1e-12 relative, floored at 1e-14 Qext for
// quantities far below Qext (Qback of a large sphere).  For an outer index
// near 1 the numerators of aₙ, bₙ are O(m − 1) and the layered series forms
// them by difference (trap m-near-1, which the homogeneous series avoids with
// its δ recurrence), so its rounding is ~ε/|m − 1| of the result, a few times
// more at a zero of ψₙ(x) (trap psi-zero): allowed 1e-15/|m − 1| where that
// is larger (layered_sphere runs such particles in long double below
// |m − 1| = 1e-3, layered_checks.hpp).
void check_close(const mie::Efficiencies<double>& got, const mie::Efficiencies<double>& want, cd m_outer) {
  const double relative = std::max(1e-12, 1e-15 / std::abs(m_outer - 1.0));
  const auto check = [&](const char* name, double a, double b) {
    INFO(name << " " << std::setprecision(17) << a << " vs " << b);
    CHECK(std::abs(a - b) <= std::max(relative * std::abs(b), 1e-14 * std::abs(want.qext)));
  };
  check("qext", got.qext, want.qext);
  check("qsca", got.qsca, want.qsca);
  check("qabs", got.qabs, want.qabs);
  check("qback", got.qback, want.qback);
  check("g", got.g, want.g);
}

const std::vector<double> kX = {1e-4, 0.1, 1.0, 4.493409457909064, 10.0, 94.24777960769377, 300.0};
const std::vector<cd> kM = {{1.0001, 0}, {1.33, 1e-8}, {1.5, 0.1}, {1.75, 0.44}, {10, 10}};

}  // namespace

TEST_CASE("one layer is sphere() itself, bit for bit", "[mie][layered]") {
  for (double x : kX)
    for (const cd& m : kM) {
      INFO("x = " << x << ", m = " << m);
      const auto a = mie::layered_sphere({x}, {m});
      const auto b = mie::sphere(x, m);
      CHECK(same_bits(a.qext, b.qext));
      CHECK(same_bits(a.qsca, b.qsca));
      CHECK(same_bits(a.qabs, b.qabs));
      CHECK(same_bits(a.qback, b.qback));
      CHECK(same_bits(a.g, b.g));
      CHECK(a.terms == b.terms);
    }
  const auto a = mie::layered_sphere(mie::PerfectConductor{}, {3.0}, {});
  const auto b = mie::sphere(3.0, mie::PerfectConductor{});
  CHECK(same_bits(a.qext, b.qext));
  CHECK(same_bits(a.qback, b.qback));
}

TEST_CASE("shell index equal to the core's gives the homogeneous sphere to rounding", "[mie][layered]") {
  for (double x : kX)
    for (const cd& m : kM)
      for (double f : {1e-3, 0.5, 0.999}) {
        INFO("x = " << x << ", m = " << m << ", core x = " << f * x);
        check_close(mie::layered_sphere({f * x, x}, {m, m}), mie::sphere(x, m), m);
        check_close(mie::layered_sphere({0.3 * f * x, f * x, x}, {m, m, m}), mie::sphere(x, m), m);
      }
}

TEST_CASE("a layer of zero thickness is left out, bit for bit", "[mie][layered]") {
  const auto same = [](const mie::Efficiencies<double>& a, const mie::Efficiencies<double>& b) {
    CHECK(same_bits(a.qext, b.qext));
    CHECK(same_bits(a.qback, b.qback));
    CHECK(same_bits(a.g, b.g));
  };
  const cd other(1.5, 0.01);
  for (double x : kX)
    for (const cd& m : kM) {
      INFO("x = " << x << ", m = " << m);
      same(mie::layered_sphere({x, x}, {m, other}), mie::sphere(x, m));
      same(mie::layered_sphere({0.5 * x, 0.5 * x, x}, {other, m, cd(1.33, 0)}),
           mie::layered_sphere({0.5 * x, x}, {other, cd(1.33, 0)}));
      same(mie::layered_sphere(mie::PerfectConductor{}, {x, x}, {m}), mie::sphere(x, mie::PerfectConductor{}));
    }
  // The referee, which computes every layer, agrees: the left-out layer does nothing.
  const std::vector<double> x = {1e-4, 1e-4};
  const std::vector<cd> m = {{1.0001, 0}, other};
  const double ref = mie::layered_sphere_referee(x, m).qext.convert_to<double>();
  CHECK(std::abs(mie::layered_sphere(x, m).qext - ref) <= 1e-12 * ref);
}

TEST_CASE("a conducting core in a shell of the medium's index is a conducting sphere", "[mie][layered]") {
  // With shell index 1 the shell is the medium: the particle is a perfectly
  // conducting sphere of size parameter x0, whose efficiencies refer to π r0²
  // and so scale by (x0/x1)² (g does not).
  for (double x0 : {0.05, 1.0, 7.5, 60.0}) {
    const double x1 = 1.7 * x0, scale = (x0 / x1) * (x0 / x1);
    const auto a = mie::layered_sphere(mie::PerfectConductor{}, {x0, x1}, {cd(1, 0)});
    const auto b = mie::sphere(x0, mie::PerfectConductor{});
    INFO("x0 = " << x0);
    CHECK(std::abs(a.qext - scale * b.qext) <= 1e-12 * scale * b.qext);
    CHECK(std::abs(a.qsca - scale * b.qsca) <= 1e-12 * scale * b.qsca);
    CHECK(std::abs(a.qback - scale * b.qback) <= 1e-12 * scale * b.qback + 1e-14 * scale * b.qext);
    CHECK(std::abs(a.g - b.g) <= 1e-12 * std::abs(b.g) + 1e-14);
    CHECK(std::abs(a.qabs) <= 1e-14 * a.qext);
  }
}

TEST_CASE("the angular machinery takes layered coefficients as they are", "[mie][layered]") {
  const std::vector<double> x = {2.0, 3.0, 5.0};
  const std::vector<cd> m = {{1.75, 0.44}, {1.5, 0.001}, {1.33, 1e-8}};
  mie::Extras ex;
  ex.coefficients = true;
  for (int i = 0; i <= 180; ++i) ex.angles_deg.push_back(i);
  const auto s = mie::layered_scatter(x, m, ex);
  const double xl = x.back();
  // The forward and backward amplitudes against the efficiencies (B&H 4.76, 4.82).
  CHECK(std::abs(4 * s.s1[0].real() / (xl * xl) - s.q.qext) <= 1e-13 * s.q.qext);
  CHECK(std::abs(4 * std::norm(s.s1[180]) / (xl * xl) - s.q.qback) <= 1e-12 * s.q.qback);
  // The phase function integrates to 4π and its first moment is g.
  const auto chi = mie::phase_function_moments(s);
  CHECK(std::abs(chi[0] - 1) <= 1e-13);
  CHECK(std::abs(chi[1] - s.q.g) <= 1e-13);
  const auto matrix = mie::scattering_matrix(xl, s);
  for (std::size_t j = 0; j < matrix.angles_deg.size(); ++j) {
    const double lhs = matrix.s11[j] * matrix.s11[j];
    const double rhs = matrix.s12[j] * matrix.s12[j] + matrix.s33[j] * matrix.s33[j] + matrix.s34[j] * matrix.s34[j];
    CHECK(std::abs(lhs - rhs) <= 1e-12 * lhs);  // a pure Mueller matrix
  }
  // The coefficients are the referee's.
  const auto r = mie::layered_scatter_referee(x, m, ex);
  REQUIRE(r.a.size() >= s.a.size());  // the referee sums to its own, smaller, tolerance
  for (std::size_t n = 0; n < s.a.size(); ++n) {
    const std::complex<double> ra(r.a[n].real().convert_to<double>(), r.a[n].imag().convert_to<double>());
    const std::complex<double> rb(r.b[n].real().convert_to<double>(), r.b[n].imag().convert_to<double>());
    CHECK(std::abs(s.a[n] - ra) <= 1e-13 * std::abs(ra) + 1e-16 * std::abs(r.a[0].real().convert_to<double>()));
    CHECK(std::abs(s.b[n] - rb) <= 1e-13 * std::abs(rb) + 1e-16 * std::abs(r.a[0].real().convert_to<double>()));
  }
}

TEST_CASE("extended recurrences where the rule asks for them, on request elsewhere", "[mie][layered]") {
  const std::vector<double> x = {300.0, 400.0};
  const std::vector<cd> m = {{1.75, 0.44}, {1.43, 1e-8}};
  mie::Options extended;
  extended.precision = mie::Precision::extended;
  mie::Options plain;
  plain.precision = mie::Precision::double_precision;
  check_close(mie::layered_sphere(x, m, extended), mie::layered_sphere(x, m, plain), m.back());
  mie::Options wiscombe;
  wiscombe.terms = mie::TermRule::wiscombe;
  CHECK(mie::layered_sphere(x, m, wiscombe).terms == mie::wiscombe_terms(400.0));
}

TEST_CASE("bad layers are rejected with the layer and the reason", "[mie][layered]") {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no exception)");
  };
  using V = std::vector<double>;
  using M = std::vector<cd>;
  CHECK(message([] { mie::layered_sphere(V{}, M{}); }).find("1 to 1000 layers") != std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{1, 2}, M{{1.5, 0}}); }).find("one index per") != std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{2, 1}, M{{1.5, 0}, {1.5, 0}}); }).find("layer 1") != std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{1, 2}, M{{1.5, 0}, {1.5, -0.1}}); }).find("layer 1: refractive index") !=
        std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{std::nan(""), 2}, M{{1.5, 0}, {1.5, 0}}); }).find("layer 0: size") !=
        std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{1, 3e5}, M{{1.5, 0}, {1.5, 0}}); }).find("exceeds 200000") !=
        std::string::npos);
  CHECK(message([] { mie::layered_sphere(V{1, 2e5}, M{{1.5, 0}, {100, 0}}); }).find("|m| x") != std::string::npos);
  CHECK(message([] { mie::layered_sphere(mie::PerfectConductor{}, V{1, 2}, M{}); }).find("one index per") !=
        std::string::npos);
}
