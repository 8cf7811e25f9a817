// One test per Mie trap (the named numerical pitfalls listed in
// mie/src/series.hpp, each seen in a widely used Mie code).
// Reference: the same problem solved by the 50-digit referee
// (attenuvis/mie/referee.hpp), i.e. the series in cpp_bin_float_50 for exactly
// the double inputs; 50 digits leave every cancellation below 1e-30.  The
// requirement is |q − q_ref| <= max(1e-10 |q_ref|, 1e-14 Qext_ref) for
// Qext, Qsca, Qabs, g and Qback.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/referee.hpp"

namespace {

namespace mie = attenuvis::mie;
using cd = std::complex<double>;

// Largest of |q − q_ref| / max(1e-10 |q_ref|, 1e-14 Qext_ref) over the five
// quantities: <= 1 meets the requirement.
double scaled_error(const mie::Efficiencies<double>& q, const mie::Efficiencies<mie::Referee>& r,
                    std::string* report = nullptr) {
  const double qext = static_cast<double>(r.qext);
  const double v[5] = {q.qext, q.qsca, q.qabs, q.g, q.qback};
  const double ref[5] = {static_cast<double>(r.qext), static_cast<double>(r.qsca), static_cast<double>(r.qabs),
                         static_cast<double>(r.g), static_cast<double>(r.qback)};
  const char* names[5] = {"qext", "qsca", "qabs", "g", "qback"};
  double worst = 0;
  std::ostringstream os;
  os.precision(17);
  for (int i = 0; i < 5; ++i) {
    const double allowed = std::max(1e-10 * std::abs(ref[i]), 1e-14 * qext);
    const double e = std::isfinite(v[i]) ? std::abs(v[i] - ref[i]) / allowed : INFINITY;
    worst = std::max(worst, e);
    os << names[i] << " " << v[i] << " ref " << ref[i] << " (" << e << ")  ";
  }
  if (report) *report = os.str();
  return worst;
}

void check_against_referee(double x, cd m, const mie::Options& options = {}) {
  std::string report;
  const double e = scaled_error(mie::sphere(x, m, options), mie::sphere_referee(x, m), &report);
  INFO("x=" << x << " m=" << m << ": " << report);
  CHECK(e <= 1.0);
}

}  // namespace

TEST_CASE("trap truncation: the series is summed until converged, not to Wiscombe's N", "[mie][trap]") {
  // Guards against stopping at N = x + 4.05 x^{1/3} + 2, which leaves ~1e-10 in
  // Qext and ~1e-8 in Qback for absorbing spheres.  Both rules are compared with
  // the converged 50-digit referee: ours must pass, and the test must be able to
  // tell (Wiscombe's N must visibly fail here, else the case proves nothing).
  for (double x : {30.0, 100.0, 1000.0}) {
    const cd m(1.5, 1.0);
    check_against_referee(x, m);
    mie::Options wiscombe;
    wiscombe.terms = mie::TermRule::wiscombe;
    const auto w = mie::sphere(x, m, wiscombe);
    const auto r = mie::sphere_referee(x, m);
    INFO("x=" << x);
    CHECK(std::abs(w.qback - static_cast<double>(r.qback)) > 1e-9 * static_cast<double>(r.qback));
  }
}

TEST_CASE("trap start-value: D_n(mx) starts from Lentz's continued fraction, not from 0", "[mie][trap]") {
  // Guards against the downward recurrence started at max(N, |mx|) + 15 from
  // zero, which at x = 1e4, m = 1.33 + 1e-5 i gives Qsca = 1.718034 instead of
  // 1.723857, because the recurrence has not forgotten its start.
  const double x = 1e4;
  const cd m(1.33, 1e-5);
  check_against_referee(x, m);
  CHECK(mie::sphere(x, m).qsca == Approx(1.723857).epsilon(5e-7));
  // Highly absorbing, |mx| = 1.5e7 >> N: only a start near N is affordable.
  check_against_referee(x, cd(1.5, 1000));
}

TEST_CASE("trap start-value: k = 1000 at x = 1e6 (|mx| = 1e9) against the referee", "[mie][trap][slow]") {
  // A downward start at |mx| would need 1e9 steps; the Lentz start at N ≈ x
  // converges in a few hundred because Im(mx) is large.  (~40 s: referee.)
  check_against_referee(1e6, cd(1.5, 1000));
}

TEST_CASE("trap small-x: small x keeps Qext positive and accurate (no psi_1 = sin x/x - cos x)", "[mie][trap]") {
  // Guards against the cancellation in ψ₁(x) = sin x/x − cos x (and in the
  // leading 1/x terms of m Dₙ(mx) − Dₙ(x)), which makes one code return
  // negative Qext below x ≈ 3e-3.  Non-absorbing m is the hard case: Qext = Qsca
  // ~ x⁴ must come out of Re(aₙ) ~ x⁶.
  for (double x : {1e-8, 1e-6, 1e-4, 3e-3, 0.05}) {
    for (cd m : {cd(1.5, 0), cd(1.33, 1e-8), cd(1.5, 0.1), cd(0.75, 0)}) {
      const auto q = mie::sphere(x, m);
      INFO("x=" << x << " m=" << m);
      CHECK(q.qext > 0);
      check_against_referee(x, m);
    }
  }
}

TEST_CASE("trap m-near-1: m -> 1 keeps full relative accuracy (difference recurrence)", "[mie][trap]") {
  // Guards against forming m² − 1 and the numerators Dₙ(mx)/m − Dₙ(x) by
  // cancellation (two codes have a 6e-13 floor at n = 1.0001).  Every quantity
  // scales like (m−1)² or (m−1), so an absolute floor would hide the trap.
  for (double x : {1e-6, 0.1, 3.0, 40.0, 1000.0})
    for (cd m : {cd(1 + 1e-6, 0), cd(1.0001, 0), cd(1 + 1e-6, 1e-8), cd(1 - 1e-6, 0)}) check_against_referee(x, m);
}

TEST_CASE("trap psi-zero: m -> 1 at a zero of psi_n(x)", "[mie][trap]") {
  // At a zero of ψₙ(x) (doubles nearest the zeros of J_{3/2}, J_{5/2}: 4.4934…,
  // 6.9879…, mpmath 40 digits) yₙ(x) = ψₙ₊₁/ψₙ comes from a cancelling
  // difference; in all-double arithmetic m = 1 + 1e-7 then misses by 3× the
  // requirement in Qext (found by a scan), hence extended-precision recurrences.
  for (double x : {4.493409457909064, 6.9879320005005194})
    for (cd m : {cd(1 + 1e-7, 0), cd(1 + 1e-6, 0), cd(1 - 1e-6, 0)}) check_against_referee(x, m);
}

TEST_CASE("trap large-kx: large k x neither overflows nor loses accuracy", "[mie][trap]") {
  // Guards against unscaled ψₙ(mx) ~ e^{kx} (k x up to 1e9 here).
  for (double x : {0.01, 1.0, 100.0, 2000.0})
    for (cd m : {cd(1.5, 1000), cd(10, 1000), cd(10, 10), cd(0.75, 30)}) check_against_referee(x, m);
  // x = 1e6: no referee here (see the [slow] case above); the large-sphere
  // limit Qext → 2 (extinction paradox, B&H §4.4.1) holds to O(x^{-2/3}).
  for (cd m : {cd(1.5, 1000), cd(10, 1000), cd(0.75, 1000)}) {
    const auto q = mie::sphere(1e6, m);
    INFO("m=" << m);
    REQUIRE(std::isfinite(q.qext));
    REQUIRE(std::isfinite(q.qback));
    CHECK(std::abs(q.qext - 2) < 1e-3);
    CHECK(q.qabs > 0);
    CHECK(q.qabs < 1);
  }
}

TEST_CASE("trap sin-zero: x at a zero of psi_0 = sin x keeps R_n = psi_n/xi_n accurate", "[mie][trap]") {
  // Guards against reaching ψ₁ as sin x · y₀ with y₀ = ψ₁/ψ₀ from the downward
  // recurrence, where 1/y₀ = 3/x − y₁ cancels: at x = 182.21237390820801 (58π
  // to sin x = 2.5e-18, mpmath) that gave NaN Qext; at 6.283185307179585 (2π,
  // sin x = −1.1e-15) Qext 5.04 for 3.92.  Dense sweeps: test_mie_sweep.cpp.
  for (double x : {6.283185307179585, 94.24777960769377, 182.21237390820801})
    for (cd m : {cd(1.33, 0), cd(1.5, 0.1), cd(1.0001, 0)}) check_against_referee(x, m);
}
