// The amplitudes S1(θ), S2(θ) of the Mie series at the requested angles,
// accumulated block by block as the series runs (template implementation
// detail of series.hpp).
//
// B&H 4.74: S1 = Σ (2n+1)/(n(n+1)) (aₙ πₙ + bₙ τₙ), S2 = Σ (2n+1)/(n(n+1)) (aₙ τₙ + bₙ πₙ),
// with the angular functions from B&H 4.47:
//   πₙ = ((2n−1) μ πₙ₋₁ − n πₙ₋₂)/(n − 1),  π₀ = 0, π₁ = 1,   τₙ = n μ πₙ − (n+1) πₙ₋₁.
// Each angle's recurrence is independent of the others, so for double the
// inner loop runs over the angles and is vectorised (angular_sums_double.cpp,
// one clone per instruction set, the same IEEE operations on every CPU);
// the angles' state is kept as separate real arrays for that.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include <boost/math/special_functions/cos_pi.hpp>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/term_block.hpp"

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

// The state of the double sums, one entry per angle.
struct AngularArrays {
  std::vector<double> mu, pi_prev, pi_cur, s1_re, s1_im, s2_re, s2_im;
};

// Adds orders first .. first + count − 1 (coefficients in t) to s
// (mie/src/angular_sums_double.cpp).
void angular_block_double(std::size_t first, std::size_t count, const TermOutputs<double>& t, AngularArrays& s);

template <class Real>
class AngularSums {
 public:
  using C = Complex<Real>;
  AngularSums(const std::vector<double>& angles_deg, Scattering<Real>& out)
      : out_(out), mu_(angle_cosines<Real>(angles_deg)) {
    const std::size_t na = angles_deg.size();
    pi_prev_.assign(na, Real(0));
    pi_cur_.assign(na, Real(1));
    out_.s1.assign(na, C(Real(0)));
    out_.s2.assign(na, C(Real(0)));
  }
  void add_block(std::size_t first, std::size_t count, const TermOutputs<Real>& t) {
    for (std::size_t i = 0; i < count; ++i) add(first + i, C(t.a_re[i], t.a_im[i]), C(t.b_re[i], t.b_im[i]));
  }
  void finish() {}

 private:
  void add(std::size_t n, const C& a, const C& b) {
    const Real rn = Real(n), f = Real(2 * n + 1) / (rn * (rn + 1));
    for (std::size_t j = 0; j < mu_.size(); ++j) {
      Real pi_n = pi_cur_[j];
      if (n >= 2) {
        pi_n = (Real(2 * n - 1) * mu_[j] * pi_cur_[j] - rn * pi_prev_[j]) / Real(n - 1);
        pi_prev_[j] = pi_cur_[j];
        pi_cur_[j] = pi_n;
      }
      const Real tau = rn * mu_[j] * pi_n - (rn + 1) * pi_prev_[j];
      const C fa = a * f, fb = b * f;
      out_.s1[j] += fa * pi_n + fb * tau;
      out_.s2[j] += fa * tau + fb * pi_n;
    }
  }
  Scattering<Real>& out_;
  std::vector<Real> mu_, pi_prev_, pi_cur_;
};

// Double: the same operations per angle as the template above, on real
// arrays, in the vectorised clones.
template <>
class AngularSums<double> {
 public:
  AngularSums(const std::vector<double>& angles_deg, Scattering<double>& out) : out_(out) {
    const std::size_t na = angles_deg.size();
    s_.mu = cached_angle_cosines(angles_deg);
    s_.pi_prev.assign(na, 0.0);
    s_.pi_cur.assign(na, 1.0);
    for (auto* v : {&s_.s1_re, &s_.s1_im, &s_.s2_re, &s_.s2_im}) v->assign(na, 0.0);
  }
  void add_block(std::size_t first, std::size_t count, const TermOutputs<double>& t) {
    angular_block_double(first, count, t, s_);
  }
  void finish() {
    const std::size_t na = s_.mu.size();
    out_.s1.resize(na);
    out_.s2.resize(na);
    for (std::size_t j = 0; j < na; ++j) {
      out_.s1[j] = Complex<double>(s_.s1_re[j], s_.s1_im[j]);
      out_.s2[j] = Complex<double>(s_.s2_re[j], s_.s2_im[j]);
    }
  }

 private:
  Scattering<double>& out_;
  AngularArrays s_;
};

}  // namespace attenuvis::mie::detail
