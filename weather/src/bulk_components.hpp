// The components of the bulk-optics panel sums (bulk_optics.cpp): which
// integrals one set of efficiency evaluations feeds, where the optional ones
// sit, and the scale each error is measured against.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"

namespace attenuvis::weather::detail {

// Components integrated together: ext, sca, abs, g*sca, asymptotic-bound,
// the weight pi r^2 n(r) alone (the geometric cross-section of the panel),
// Q_back/(4 pi), then as requested chi_l Q_sca (l = 0..L), p(theta_j) Q_sca
// and the expansion's coefficients times Q_sca.
constexpr int kExt = 0, kSca = 1, kAbs = 2, kGSca = 3, kAsym = 4, kWeight = 5, kBack = 6, kFixed = 7;
using Vec = std::vector<double>;

// The coefficient vectors of the scattering-matrix expansion, in the order
// Efficiency::expansion concatenates them: alpha1..alpha4, beta1, beta2.
// The structured binding names every member of MatrixExpansion, so the
// count cannot drift from the struct.
constexpr int kExpansionParts = 6;
inline std::array<std::vector<double>*, kExpansionParts> expansion_parts(MatrixExpansion& e) {
  auto& [alpha1, alpha2, alpha3, alpha4, beta1, beta2] = e;
  return {&alpha1, &alpha2, &alpha3, &alpha4, &beta1, &beta2};
}
constexpr const char* kExpansionPartNames[kExpansionParts] = {"alpha1", "alpha2", "alpha3", "alpha4", "beta1", "beta2"};

// Where the optional components sit, and which components the tolerances
// govern, each with the scale its error is measured against.
struct Layout {
  bool back = false;
  int moments = 0;  // L + 1, or 0
  int angles = 0;
  int expansion = 0;  // kExpansionParts (L + 1): alpha1..4, beta1, beta2
  explicit Layout(const QuadratureSettings& s)
      : back(s.backscatter), moments(s.legendre_moments >= 0 ? s.legendre_moments + 1 : 0),
        angles(static_cast<int>(s.angles_deg.size())), expansion(s.polarised ? kExpansionParts * moments : 0) {}
  int moment(int l) const { return kFixed + l; }
  int angle(int j) const { return kFixed + moments + j; }
  int expansion_at(int i) const { return kFixed + moments + angles + i; }
  int size() const { return kFixed + moments + angles + expansion; }
  bool angular(int c) const { return c >= kBack; }
  // The components whose errors must meet the tolerances.
  std::vector<int> checked() const {
    std::vector<int> c{kExt, kSca, kAbs, kGSca};
    if (back) c.push_back(kBack);
    for (int i = kFixed; i < size(); ++i) c.push_back(i);
    return c;
  }
  bool is_moment(int c) const { return c >= kFixed && c < kFixed + moments; }
  // sigma_ext for ext/sca/abs, sigma_sca for g and the expansion (absolute
  // on the normalised value), the component itself for beta_pi and
  // p(theta), and for chi_l the larger of the component and
  // kMomentFloor sigma_sca (moment_scale).
  double scale(int c, const Vec& v) const {
    if (is_moment(c)) return std::max(std::abs(v[kSca]), 1e-300) * moment_scale(v[c] / v[kSca]);
    if (c == kGSca || c >= kFixed + moments + angles) return std::max(std::abs(v[kSca]), 1e-300);
    if (c == kBack || c >= kFixed + moments) return std::max(std::abs(v[c]), 1e-300);
    return std::max(std::abs(v[kExt]), 1e-300);
  }
  // chi_l is held to the angular tolerance relative to itself down to
  // |chi_l| = kMomentFloor, and below that to the tolerance times the floor,
  // absolute (chi_0 = 1).  The moments that shape the phase function are so
  // each relative; the tail of a small drop's moments (chi_32 of radiation
  // fog at 10.6 um is 3e-18) would otherwise ask for digits that the
  // per-drop moments, rounded relative to chi_0, do not hold.
  static constexpr double kMomentFloor = 1e-3;
  static double moment_scale(double chi) { return std::isfinite(chi) ? std::max(std::abs(chi), kMomentFloor) : 1.0; }
};

// The relative tolerance of g, beta_pi, chi_l, p(theta) and the expansion:
// QuadratureSettings::angular_tolerance, or max(rel_tolerance, 1e-6) when it is 0.
double angular_tolerance(const QuadratureSettings& s);

}  // namespace attenuvis::weather::detail
