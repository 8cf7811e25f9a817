// One Gauss-Kronrod panel of an integral of S(0; x) w(x) along a path in the
// complex size-parameter plane, and the refinement around it: the building
// blocks shared by the contour rule of analytic distributions
// (contour_extinction.cpp) and of tabulated ones (segmented_contour.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/io/check.hpp"
#include "attenuvis/io/number_text.hpp"

#include "attenuvis/mie/forward_amplitude.hpp"
#include "gauss_kronrod_rule.hpp"
#include "product_rule.hpp"

namespace attenuvis::weather::detail {

// S(0) in double arithmetic where its rounding bound (~1e-11 |S(0)| at height
// 4 and x <= 1000, mie/forward_amplitude.hpp) leaves the tolerance a 100-fold
// margin; long double (4x slower) otherwise.
inline mie::Precision contour_arithmetic(double rel_tolerance, double height) {
  return rel_tolerance >= 1e-9 && height <= 4 ? mie::Precision::double_precision : mie::Precision::extended;
}

// Relative amplitude left of the resonance ripple at height h above the real
// axis: exp(-2 pi h / dx), dx the ripple period in x (Chylek 1976); for
// n <= 1 (no whispering-gallery modes) dx = 1, the n -> 1 limit.
inline double ripple_residual(std::complex<double> m, double h) {
  const double n = m.real();
  const double root = n > 1 ? std::sqrt(n * n - 1) : 0.0;
  const double period = root > 1e-8 ? std::atan(root) / root : 1.0;
  return std::exp(-2 * boost::math::constants::pi<double>() * h / period);
}

// 0, 1, ..., n - 1: every panel, for the verification pass that halves them all.
inline std::vector<std::size_t> every_index(std::size_t n) {
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), std::size_t(0));
  return all;
}

struct PathPanel {
  double a = 0, b = 0;            // parameter interval of the path
  std::complex<double> kronrod{}; // integral over the panel
  double error = 0;               // |K - G| (the modulus: see evaluate_path_panel)
  double rounding = 0;            // bound on the rounding error of the panel's integral
  double q_max = 0;               // max |4 S(0) / x^2| sampled
  double magnitude_max = 0;       // max ForwardAmplitude::magnitude sampled
  std::size_t evaluations = 0;
};

// The nodes of `nodes` (ordered_nodes) mapped to [a, b], and the path's
// points there: x[j] = point(t_j).
template <class Point>
void path_points(const OrderedNodes& nodes, double a, double b, const Point& point, std::complex<double>* x) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  for (std::size_t j = 0; j < nodes.u.size(); ++j) x[j] = point(mid + nodes.u[j] * half);
}

// The panel's Gauss-Kronrod sums from S(0) at its points (path_points):
// of S(0; x(t)) w(x(t)) x'(t) over [a, b], x'(t) = jacobian(t), w = weight(x).
template <class Jacobian, class Weight>
PathPanel path_panel_sums(const OrderedNodes& nodes, double a, double b, const std::complex<double>* x,
                          const mie::ForwardAmplitude* fa, const Jacobian& jacobian, const Weight& weight) {
  using Complex = std::complex<double>;
  PathPanel p;
  p.a = a;
  p.b = b;
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  const std::size_t count = nodes.u.size();
  Complex k{}, g{};
  double worst_rounding = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const Complex jac = jacobian(mid + nodes.u[j] * half);
    const Complex w = weight(x[j]) * jac;
    const Complex v = fa[j].s0 * w;
    k += nodes.kronrod_weight[j] * v;
    g += nodes.gauss_weight[j] * v;
    worst_rounding = std::max(worst_rounding, fa[j].rounding_bound() * std::abs(w));
    p.q_max = std::max(p.q_max, 4 * std::abs(fa[j].s0) / std::norm(x[j]));
    p.magnitude_max = std::max(p.magnitude_max, fa[j].magnitude);
  }
  p.evaluations = count;
  p.kronrod = half * k;
  // The modulus, not |Re(K - G)|: the real part of a complex difference can
  // vanish by accident while the real part of the error does not.
  p.error = half * std::abs(k - g);
  p.rounding = (b - a) * worst_rounding;  // width x largest sampled bound
  return p;
}

// Gauss-Kronrod on [a, b] of S(0; x(t)) w(x(t)) x'(t) dt, x(t) = point(t),
// x'(t) = jacobian(t), w = weight(x) (complex).  The nodes are visited in
// increasing t, so S(0) is batched over neighbouring |x|.
template <class Point, class Jacobian, class Weight>
PathPanel evaluate_path_panel(const Rule& rule, double a, double b, const Point& point, const Jacobian& jacobian,
                              const Weight& weight, std::complex<double> m, mie::Precision arithmetic) {
  const OrderedNodes nodes = ordered_nodes(rule);
  const std::size_t count = nodes.u.size();
  std::vector<std::complex<double>> x(count);
  path_points(nodes, a, b, point, x.data());
  std::vector<mie::ForwardAmplitude> fa(count);
  mie::forward_amplitudes(x.data(), count, m, arithmetic, fa.data());
  return path_panel_sums(nodes, a, b, x.data(), fa.data(), jacobian, weight);
}

// The same panel by product integration (product_rule.hpp): S(0; x(t)) x'(t)
// against a weight that is linear in x on each of `segments` and may jump
// between them.  The segments are given in t, {t0, t1, alpha, beta}, with the
// weight alpha + beta (x - c) about the panel's centre c = (a + b) / 2 (so
// that a steep, short segment far from x = 0 loses no digits to alpha).
template <class Point, class Jacobian>
PathPanel evaluate_product_panel(const ProductRule& rule, double a, double b,
                                 const std::vector<ProductRule::Segment>& segments, const Point& point,
                                 const Jacobian& jacobian, std::complex<double> m, mie::Precision arithmetic) {
  using Complex = std::complex<double>;
  PathPanel p;
  p.a = a;
  p.b = b;
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  const std::size_t count = rule.size();
  std::vector<Complex> x(count), centred(count);
  for (std::size_t j = 0; j < count; ++j) x[j] = point(mid + rule.node(j) * half), centred[j] = x[j] - mid;
  std::vector<ProductRule::Segment> in_u(segments);
  for (auto& s : in_u) s.u0 = (s.u0 - mid) / half, s.u1 = (s.u1 - mid) / half;
  std::vector<Complex> kronrod_w, gauss_w;
  rule.weights(in_u, centred, kronrod_w, gauss_w);
  std::vector<mie::ForwardAmplitude> fa(count);
  mie::forward_amplitudes(x.data(), count, m, arithmetic, fa.data());
  Complex k{}, g{};
  double rounding = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const Complex jac = jacobian(mid + rule.node(j) * half);
    const Complex v = fa[j].s0 * jac;
    k += kronrod_w[j] * v;
    g += gauss_w[j] * v;
    rounding += fa[j].rounding_bound() * std::abs(kronrod_w[j] * jac);
    p.q_max = std::max(p.q_max, 4 * std::abs(fa[j].s0) / std::norm(x[j]));
    p.magnitude_max = std::max(p.magnitude_max, fa[j].magnitude);
  }
  p.evaluations = count;
  p.kronrod = half * k;
  p.error = half * std::abs(k - g);  // the modulus, as evaluate_path_panel
  p.rounding = half * rounding;      // the linear functional's own bound: sum |omega_j| x bound_j
  return p;
}

// The panels with each panel listed in `split` (increasing indices) replaced,
// in place, by its two halves (halves[2h], halves[2h + 1] for split[h]):
// the refinement step of both contour rules, which keeps the panels in path
// order so that sums do not depend on how they were refined.
template <class Panel>
std::vector<Panel> with_halves(const std::vector<Panel>& panels, const std::vector<std::size_t>& split,
                               const std::vector<Panel>& halves) {
  ATTENUVIS_CHECK_EQ(halves.size(), 2 * split.size());
  std::vector<Panel> next;
  next.reserve(panels.size() + split.size());
  std::size_t h = 0;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    if (h < split.size() && split[h] == i) {
      next.push_back(halves[2 * h]);
      next.push_back(halves[2 * h + 1]);
      ++h;
    } else {
      next.push_back(panels[i]);
    }
  }
  ATTENUVIS_CHECK_EQ(h, split.size());  // every split index was a panel's, in increasing order
  return next;
}

// Adaptive refinement with verification by halving, the loop both contour
// rules run.  refine(panels) splits until the panels' own estimate meets the
// target.  Without `verify` that is the answer.  With it, every panel is
// halved once (halve_all) and the change of the sum is charged on top of the
// fine sum's own estimate: |K - G| stalls where the integrand carries
// structure no panel resolves, so the coarse error is measured, not guessed.
// accept(fine) says whether the verified sum meets the target (and throws
// when it cannot: non-finite sums, the evaluation budget); if not, the fine
// panels are refined again.
template <class Panel, class Refine, class SumsOf, class HalveAll, class Accept>
auto refined_sums(std::vector<Panel>& panels, bool verify, Refine refine, SumsOf sums, HalveAll halve_all,
                  Accept accept) {
  for (;;) {
    refine(panels);
    if (!verify) return sums(panels);
    const auto coarse = sums(panels).total;
    std::vector<Panel> halves = halve_all(panels);
    auto fine = sums(halves);
    fine.error += std::abs((fine.total - coarse).real());
    if (accept(fine)) return fine;
    panels.swap(halves);
  }
}

// Throws once a contour rule (`rule`, e.g. "sigma_ext by contour") has spent
// more than max_evaluations Mie evaluations with `what` (its error estimate,
// relative to the sum) still above the tolerance.
inline void check_evaluation_budget(const char* rule, const char* what, double relative_error, double tolerance,
                                    std::size_t evaluations, std::size_t max_evaluations) {
  if (evaluations <= max_evaluations) return;
  throw std::runtime_error(std::string(rule) + ": " + what + " " + io::significant(relative_error, 3) +
                           " (relative) still above the tolerance " + io::significant(tolerance, 3) + " after " +
                           std::to_string(evaluations) + " Mie evaluations");
}

}  // namespace attenuvis::weather::detail
