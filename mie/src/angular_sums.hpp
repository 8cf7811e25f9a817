// The amplitudes S1(θ), S2(θ) of the Mie series at the requested angles,
// accumulated block by block as the series runs (template implementation
// detail of series.hpp).
//
// B&H 4.74: S1 = Σ (2n+1)/(n(n+1)) (aₙ πₙ + bₙ τₙ), S2 = Σ (2n+1)/(n(n+1)) (aₙ τₙ + bₙ πₙ),
// with the angular functions from B&H 4.47:
//   πₙ = ((2n−1) μ πₙ₋₁ − n πₙ₋₂)/(n − 1),  π₀ = 0, π₁ = 1,   τₙ = n μ πₙ − (n+1) πₙ₋₁.
// Each angle's recurrence is independent of the others, so the inner loop
// runs over the angles, on separate real arrays; for double it is compiled
// once per instruction set and vectorised (angular_sums_double.cpp, the same
// IEEE operations on every CPU).
#pragma once

#include <complex>
#include <cstddef>
#include <type_traits>
#include <vector>

#include <boost/math/special_functions/cos_pi.hpp>

#include "attenuvis/mie.hpp"
#include "term_block.hpp"

namespace attenuvis::mie::detail {

// μ = cos θ, exact at 90° and 180° (cos_pi).
template <class Real>
std::vector<Real> angle_cosines(const std::vector<double>& angles_deg) {
  std::vector<Real> mu(angles_deg.size());
  for (std::size_t j = 0; j < mu.size(); ++j) mu[j] = boost::math::cos_pi(Real(angles_deg[j]) / Real(180));
  return mu;
}

// The cosines of the last angle list this thread asked for.  A size
// distribution evaluates thousands of spheres at one list, and cos_pi of a
// double runs in long double (Boost's promotion policy): recomputing them per
// sphere was a sixth of a phase-function table's time.
inline const std::vector<double>& cached_angle_cosines(const std::vector<double>& angles_deg) {
  thread_local std::vector<double> degrees, cosines;
  if (degrees != angles_deg) {
    cosines = angle_cosines<double>(angles_deg);
    degrees = angles_deg;
  }
  return cosines;
}

// The state of the sums, one entry per angle.
template <class Real>
struct AngularArrays {
  std::vector<Real> mu, pi_prev, pi_cur, s1_re, s1_im, s2_re, s2_im;
};

// Adds orders first .. first + count − 1 (coefficients in t) to s.
template <class Real>
ATTENUVIS_MIE_INLINE void angular_block(std::size_t first, std::size_t count, const TermOutputs<Real>& t,
                                        AngularArrays<Real>& s) {
  const std::size_t na = s.mu.size();
  const Real* mu = s.mu.data();
  Real* pi_prev = s.pi_prev.data();
  Real* pi_cur = s.pi_cur.data();
  Real *s1r = s.s1_re.data(), *s1i = s.s1_im.data(), *s2r = s.s2_re.data(), *s2i = s.s2_im.data();
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t n = first + i;
    const Real rn = Real(n), rn1 = rn + 1, f = Real(2 * n + 1) / (rn * rn1);
    const Real far = t.a_re[i] * f, fai = t.a_im[i] * f, fbr = t.b_re[i] * f, fbi = t.b_im[i] * f;
    // π₀ = 0, π₁ = 1 are the initial arrays; from n = 2 on, πₙ by its recurrence.
    const bool recur = n >= 2;
    const Real w = Real(2 * n - 1), d = recur ? Real(n - 1) : Real(1);
    // ivdep: the arrays are distinct, which GCC cannot prove through the
    // vectors' pointers.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
    for (std::size_t j = 0; j < na; ++j) {
      Real pi_n = pi_cur[j], prev = pi_prev[j];
      if (recur) {
        prev = pi_n;
        pi_n = (w * mu[j] * pi_cur[j] - rn * pi_prev[j]) / d;
        pi_prev[j] = prev;
        pi_cur[j] = pi_n;
      }
      const Real tau = rn * mu[j] * pi_n - rn1 * prev;
      s1r[j] += far * pi_n + fbr * tau;
      s1i[j] += fai * pi_n + fbi * tau;
      s2r[j] += far * tau + fbr * pi_n;
      s2i[j] += fai * tau + fbi * pi_n;
    }
  }
}

// angular_block for double, one clone per instruction set
// (mie/src/angular_sums_double.cpp).
void angular_block_double(std::size_t first, std::size_t count, const TermOutputs<double>& t,
                          AngularArrays<double>& s);

template <class Real>
class AngularSums {
 public:
  AngularSums(const std::vector<double>& angles_deg, Scattering<Real>& out) : out_(out) {
    const std::size_t na = angles_deg.size();
    if constexpr (std::is_same_v<Real, double>) s_.mu = cached_angle_cosines(angles_deg);
    else s_.mu = angle_cosines<Real>(angles_deg);
    s_.pi_prev.assign(na, Real(0));
    s_.pi_cur.assign(na, Real(1));
    for (auto* v : {&s_.s1_re, &s_.s1_im, &s_.s2_re, &s_.s2_im}) v->assign(na, Real(0));
  }
  void add_block(std::size_t first, std::size_t count, const TermOutputs<Real>& t) {
    if constexpr (std::is_same_v<Real, double>) angular_block_double(first, count, t, s_);
    else angular_block(first, count, t, s_);
  }
  // Writes S1, S2 into the Scattering given to the constructor.
  void finish() {
    const std::size_t na = s_.mu.size();
    out_.s1.resize(na);
    out_.s2.resize(na);
    for (std::size_t j = 0; j < na; ++j) {
      out_.s1[j] = Complex<Real>(s_.s1_re[j], s_.s1_im[j]);
      out_.s2[j] = Complex<Real>(s_.s2_re[j], s_.s2_im[j]);
    }
  }

 private:
  Scattering<Real>& out_;
  AngularArrays<Real> s_;
};

}  // namespace attenuvis::mie::detail
