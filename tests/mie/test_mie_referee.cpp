// The double-precision Mie product against the 50-digit referee
// (attenuvis/mie/referee.hpp: the same series in cpp_bin_float_50) over the
// stress grid:  x in the decades 1e-8 ... 1e6 plus non-round values,
//               n in {1+1e-6, 1.0001, 1.33, 1.5, 2, 10, 0.75},
//               k in {0, 1e-8, 1e-5, 0.1, 1, 10, 1000}.
// Requirement: Qext, Qsca, Qabs, g, Qback within 1e-10 relative, with an
// absolute floor of 1e-14 Qext only where the quantity itself is that small, i.e.
//     |q - q_ref| <= max(1e-10 |q_ref|, 1e-14 Qext_ref),
// and no NaN, no infinity, no exception anywhere.
//
// Cost (Release, one core of the development machine): the referee takes about
// 25 us per series term (~x terms), i.e. 0.3 s at x = 1e4, 2.6 s at 1e5, ~30 s at
// 1e6.  The normal run (also under ASan) covers x <= 1e3 with every m (~3 s in
// Release); the [slow] cases (Release only, ~1 min) add x = 1e4 for every m,
// x = 12345.6 and 1e5 for one m per n and x = 1e6 for m = 1.33 + 1e-8 i, plus a
// NaN/infinity sweep at x = 1e6 with two k per n.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/referee.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

const std::vector<double> kN = {1.0 + 1e-6, 1.0001, 1.33, 1.5, 2.0, 10.0, 0.75};
const std::vector<double> kK = {0.0, 1e-8, 1e-5, 0.1, 1.0, 10.0, 1000.0};

std::vector<cd> all_m() {
  std::vector<cd> ms;
  for (double n : kN)
    for (double k : kK) ms.emplace_back(n, k);
  return ms;
}

// Normalised error of one quantity: <= 1 means "within the requirement".
double scaled_error(double q, double ref, double qext_ref) {
  if (!std::isfinite(q)) return INFINITY;
  const double allowed = std::max(1e-10 * std::abs(ref), 1e-14 * std::abs(qext_ref));
  if (allowed == 0) return q == 0 ? 0 : INFINITY;
  return std::abs(q - ref) / allowed;
}

struct PointResult {
  double worst = 0;         // max over the five quantities of scaled_error (<= 1 passes)
  std::string worst_name;
  std::string detail;       // all five values when it fails
};

PointResult compare_with_referee(double x, cd m) {
  const mie::Efficiencies<double> d = mie::sphere(x, m);
  const mie::Efficiencies<mie::Referee> r = mie::sphere_referee(x, m);
  const double qext_ref = r.qext.convert_to<double>();
  struct Q {
    const char* name;
    double got;
    double ref;
  } qs[] = {{"qext", d.qext, qext_ref},
            {"qsca", d.qsca, r.qsca.convert_to<double>()},
            {"qabs", d.qabs, r.qabs.convert_to<double>()},
            {"g", d.g, r.g.convert_to<double>()},
            {"qback", d.qback, r.qback.convert_to<double>()}};
  PointResult res;
  std::ostringstream os;
  os << std::setprecision(17);
  for (const Q& q : qs) {
    const double e = scaled_error(q.got, q.ref, qext_ref);
    os << q.name << " " << q.got << " ref " << q.ref << " (x1e-10 err " << e << "); ";
    if (!(e <= res.worst)) {
      res.worst = e;
      res.worst_name = q.name;
    }
  }
  res.detail = os.str();
  return res;
}

// Runs the grid xs × ms, one CHECK per point, and prints the largest error seen.
void check_grid(const std::vector<double>& xs, const std::vector<cd>& ms, const char* label) {
  double worst = 0;
  std::string where;
  for (double x : xs)
    for (const cd& m : ms) {
      PointResult p;
      INFO("x = " << std::setprecision(17) << x << ", m = " << m.real() << " + " << m.imag() << "i");
      REQUIRE_NOTHROW(p = compare_with_referee(x, m));
      INFO(p.detail);
      CHECK(p.worst <= 1.0);
      if (!(p.worst <= worst)) {
        worst = p.worst;
        std::ostringstream os;
        os << "x = " << x << ", m = " << m.real() << " + " << m.imag() << "i (" << p.worst_name << ")";
        where = os.str();
      }
    }
  std::cout << "[mie referee] " << label << ": " << xs.size() * ms.size()
            << " points, largest error " << worst * 1e-10 << " (relative, floored at 1e-4 Qext) at "
            << where << "\n";
}

}  // namespace

TEST_CASE("double vs 50-digit referee: x = 1e-8 ... 1e3, every m", "[mie][referee]") {
  const std::vector<double> xs = {1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 3.7e-3, 1e-2, 0.0537, 0.1,
                                  0.7071, 1.0,  3.7,  10.0, 41.3, 100.0, 777.7,  1e3};
  check_grid(xs, all_m(), "x <= 1e3");
}

TEST_CASE("double vs 50-digit referee: x at zeros of psi_n(x)", "[mie][referee]") {
  // psi_n(x) = x j_n(x) has zeros for every n < x, so some psi_n (n <= N) is small
  // for any x and exactly zero at these x.  A series written in ratios such as
  // psi_{n-1}/psi_n must stay accurate through their poles.  The x below are the
  // doubles nearest to zeros of J_{n+1/2}(x) (mpmath findroot, 40 digits):
  //   n = 1: 4.4934094579090641753   n = 10: 15.033469303743438064
  //   n = 35: 41.913091196344584765  n = 50: 57.638686770302609953
  //   n = 200: 211.53805588885715699 n = 2000: 2041.6335055737876057
  // (The n = 35 case was first hit by a random search over 8000 (x, m) points.)
  const std::vector<double> xs = {4.493409457909064,  15.033469303743438, 41.91309119634459,
                                  57.63868677030261,  211.53805588885714, 2041.6335055737877};
  const std::vector<cd> ms = {{1.0 + 1e-6, 0.0}, {1.0001, 0.0}, {1.33, 0.0}, {1.33, 1e-8},
                              {0.75, 0.0},       {1.5, 0.1},     {10.0, 10.0}};
  check_grid(xs, ms, "zeros of psi_n");
}

TEST_CASE("double vs 50-digit referee: x = 1e4, every m", "[mie][referee][slow]") {
  check_grid({1e4}, all_m(), "x = 1e4");
}

TEST_CASE("double vs 50-digit referee: x = 12345.6 and 1e5, one k per n", "[mie][referee][slow]") {
  // One absorption per n, cycling through the k values so every k appears.
  std::vector<cd> ms;
  for (size_t i = 0; i < kN.size(); ++i) ms.emplace_back(kN[i], kK[i % kK.size()]);
  check_grid({12345.6, 1e5}, ms, "x = 12345.6, 1e5");
}

TEST_CASE("double vs 50-digit referee: x = 1e6", "[mie][referee][slow]") {
  // The weakly absorbing water-like sphere of trap start-value, where D_n(mx) and Qback are
  // hardest; one point because the referee needs ~30 s here.
  check_grid({1e6}, {cd(1.33, 1e-8)}, "x = 1e6");
}

// Qback of a sphere with m close to 1 at large x (Rayleigh–Gans–Debye regime):
// Qback ~ 1e-9 Qext comes from Σ(−1)ⁿ(2n+1)(aₙ − bₙ) with aₙ ≈ bₙ, an
// alternating sum that cancels by ~x (trap back-cancellation).  The stress
// grid's floor of 1e-14 Qext would accept any Qback there, so this grid asks
// 1e-10 of Qback relative to itself.  Forming aₙ − bₙ by subtraction missed it
// by up to 9e-10 (x = 3e3 ... 1e5, |m − 1| <= 1e-4); sphere_terms
// (term_block.hpp) forms it from a factored formula.
void check_qback_near_one(const std::vector<double>& xs, const char* label) {
  const std::vector<cd> ms = {{1.0001, 0.0}, {1.0001, 1e-8}, {0.9999, 0.0}, {1.0 + 1e-5, 0.0}, {1.00005, 1e-6}};
  double worst = 0;
  for (double x : xs)
    for (const cd& m : ms) {
      const auto d = mie::sphere(x, m);
      const double ref = mie::sphere_referee(x, m).qback.convert_to<double>();
      const double e = std::abs(d.qback - ref) / ref;
      INFO("x = " << std::setprecision(17) << x << ", m = " << m.real() << " + " << m.imag() << "i: Qback "
                  << d.qback << " ref " << ref);
      CHECK(e <= 1e-10);
      worst = std::max(worst, e);
    }
  std::cout << "[mie referee] Qback near m = 1, " << label << ": largest relative error " << worst << "\n";
}

TEST_CASE("Qback within 1e-10 of itself for |m - 1| <= 1e-4 at x = 3e3", "[mie][referee]") {
  check_qback_near_one({3e3, 4321.5}, "x = 3e3, 4321.5");
}

TEST_CASE("Qback within 1e-10 of itself for |m - 1| <= 1e-4 at x = 1e4 ... 1e5", "[mie][referee][slow]") {
  check_qback_near_one({1e4, 3.3e4, 1e5}, "x = 1e4 ... 1e5");
}

TEST_CASE("purely imaginary index n = 0 is accepted and accurate, n < 0 and m = 0 are not", "[mie][referee]") {
  // mie.hpp's contract: n >= 0, k >= 0, m != 0.  m = ik is the index of a
  // lossless Drude metal below its plasma frequency; k = sqrt(2) puts the dipole
  // surface resonance (m^2 + 2 = 0, B&H §12.1) exactly at m.
  check_grid({1e-3, 0.3, 1.0, 10.0, 150.0}, {cd(0.0, 0.5), cd(0.0, std::sqrt(2.0)), cd(0.0, 3.0)}, "n = 0");
  CHECK_THROWS_AS(mie::sphere(1.0, cd(-1e-300, 1.0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(1.0, cd(-0.5, 1.0)), std::invalid_argument);
  CHECK_THROWS_AS(mie::sphere(1.0, cd(0.0, 0.0)), std::invalid_argument);
}

TEST_CASE("no NaN, no infinity, no exception on the whole grid up to x = 1e5", "[mie][referee]") {
  const std::vector<double> xs = {1e-8, 1e-6, 1e-4, 1e-2, 1.0, 100.0, 1e4, 1e5};
  for (double x : xs)
    for (const cd& m : all_m()) {
      INFO("x = " << x << ", m = " << m.real() << " + " << m.imag() << "i");
      mie::Efficiencies<double> q;
      REQUIRE_NOTHROW(q = mie::sphere(x, m));
      CHECK(std::isfinite(q.qext));
      CHECK(std::isfinite(q.qsca));
      CHECK(std::isfinite(q.qabs));
      CHECK(std::isfinite(q.qback));
      CHECK(std::isfinite(q.qpr));
      CHECK(std::isfinite(q.g));
      CHECK(q.qsca >= 0);
      CHECK(q.qabs >= 0);
      CHECK(q.qback >= 0);
    }
}

TEST_CASE("no NaN, no infinity, no exception at x = 1e6, two k per n", "[mie][referee][slow]") {
  // Two absorptions per n (every k appears twice); all 49 would cost ~35 s.
  std::vector<cd> ms;
  for (size_t i = 0; i < kN.size(); ++i) {
    ms.emplace_back(kN[i], kK[i % kK.size()]);
    ms.emplace_back(kN[i], kK[(i + 3) % kK.size()]);
  }
  for (const cd& m : ms) {
    INFO("x = 1e6, m = " << m.real() << " + " << m.imag() << "i");
    mie::Efficiencies<double> q;
    REQUIRE_NOTHROW(q = mie::sphere(1e6, m));
    CHECK(std::isfinite(q.qext));
    CHECK(std::isfinite(q.qsca));
    CHECK(std::isfinite(q.qabs));
    CHECK(std::isfinite(q.qback));
    CHECK(std::isfinite(q.g));
    CHECK(q.qabs >= 0);
  }
}
