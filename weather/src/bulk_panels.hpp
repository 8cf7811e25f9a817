// The panels of the real-axis size integral (bulk_optics.cpp): one panel's
// Gauss-Kronrod sums of every component, or, around a resolved resonance,
// its product-rule sums (pole_rule.hpp), from one batch of efficiency
// evaluations; and how a panel is split.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include <tbb/parallel_for.h>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "bulk_components.hpp"
#include "gauss_kronrod_rule.hpp"
#include "pole_rule.hpp"
#include "resonance.hpp"

namespace attenuvis::weather::detail {

struct Panel {
  double a = 0, b = 0;  // in u = ln r
  Vec kronrod, error;
  Vec difference;       // signed K - G (without the aliasing term): errors of ratios
  Vec q_max;            // largest |component / weight| sampled (for the tails and resonance bounds)
  Vec q_lo, q_hi;       // range of component / weight sampled (the aliasing bound)
  double qext_max = 0;
  double x_span = 0;  // size-parameter width of the panel
  // A resolved resonance inside the panel (resonance_plan.hpp): its nodes and
  // weights are the product rule of pole_rule.hpp for the pole x0 - i gamma.
  bool pole = false;
  double pole_x0 = 0, pole_gamma = 0;
  std::size_t evaluations = 0;
  double max_x = 0;
  bool used_asymptotic = false;
};

class Integrator {
 public:
  Integrator(const SizeDistribution& d, double wavelength, const EfficiencyBatch& q, const QuadratureSettings& s,
             std::complex<double> m)
      : d_(d), k_(2 * boost::math::constants::pi<double>() / wavelength), q_(q), s_(s), layout_(s), rule_(rule_for(s.kronrod_points)),
        resonances_(s.estimate_resonances), resolved_x_span_(resonances_ ? 2.0 : 0.6 * s.kronrod_points), m_(m) {}

  const Layout& layout() const { return layout_; }

  // A node of a panel at u = ln r: its size parameter and the weight
  // r n(r) pi r^2 of the integrand in u.
  struct Node {
    double x = 0, w = 0;
    bool asymptotic = false;  // beyond asymptotic_x: Q_ext's large-x expansion, no Mie
    std::size_t rule = 0;     // index of its abscissa and weights in the panel's rule
  };
  Node node(double u, Panel& p) const {
    const double r = std::exp(u);
    Node nd{k_ * r, r * d_.density(r) * boost::math::constants::pi<double>() * r * r, false};
    p.max_x = std::max(p.max_x, nd.x);
    nd.asymptotic = s_.asymptotic_x > 0 && nd.x > s_.asymptotic_x;
    if (nd.asymptotic) p.used_asymptotic = true;
    return nd;
  }

  // Integrand at a node:  w {Q_ext, Q_sca, Q_abs, g Q_sca, bound, ...}, from
  // the node's efficiencies e (unused for an asymptotic node).
  Vec integrand(const Node& nd, const Efficiency& e, double& qext) const {
    const double x = nd.x, w = nd.w;
    Vec f(layout_.size(), 0.0);
    if (nd.asymptotic) {
      qext = qext_asymptotic(x);
      f[kExt] = w * qext;
      f[kAsym] = w * qext_asymptotic_bound(x, m_);
      f[kWeight] = w;
      return f;
    }
    qext = e.qext;
    f[kExt] = w * e.qext;
    f[kSca] = w * e.qsca;
    f[kAbs] = w * e.qabs;
    f[kGSca] = w * e.g * e.qsca;
    f[kWeight] = w;
    f[kBack] = w * e.qback / (4 * boost::math::constants::pi<double>());
    if (e.moments.size() < static_cast<std::size_t>(layout_.moments) ||
        e.phase.size() < static_cast<std::size_t>(layout_.angles) ||
        e.expansion.size() < static_cast<std::size_t>(layout_.expansion))
      throw std::invalid_argument("bulk optics: the efficiency function does not supply the Legendre moments or "
                                  "phase function asked for");
    for (int l = 0; l < layout_.moments; ++l) f[layout_.moment(l)] = w * e.qsca * e.moments[l];
    for (int j = 0; j < layout_.angles; ++j) f[layout_.angle(j)] = w * e.qsca * e.phase[j];
    for (int i = 0; i < layout_.expansion; ++i) f[layout_.expansion_at(i)] = w * e.qsca * e.expansion[i];
    return f;
  }

  // The panel's nodes in the rule's order (the centre, then each abscissa at
  // +xi and -xi), their efficiencies in one batch call.
  Panel evaluate(double a, double b) const {
    throw_if_cancelled(s_.cancel);  // once per panel: a few dozen Mie evaluations
    Panel p;
    p.a = a;
    p.b = b;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    std::vector<Node> nodes;
    std::vector<double> kronrod, gauss;
    for (std::size_t i = 0; i < rule_.abscissa.size(); ++i)
      for (int sgn = 0; sgn < (i == 0 ? 1 : 2); ++sgn) {
        nodes.push_back(node(mid + (sgn ? -rule_.abscissa[i] : rule_.abscissa[i]) * half, p));
        kronrod.push_back(half * rule_.kronrod_weight[i]);
        gauss.push_back(half * rule_.gauss_weight[i]);
      }
    accumulate(p, nodes, kronrod, gauss, {});
    p.x_span = k_ * (std::exp(b) - std::exp(a));
    // |K - G| estimates the error only where the rule resolves the ripple of
    // Q(x) (period pi/(n-1) ~ 9.5 in x for water) and, for nearly lossless
    // drops, the resonances that are neither resolved nor bounded (those
    // above the barrier, half-width >= ~0.05: resonance_plan.hpp); panels
    // wider than resolved_x_span_ can alias them.  There, since K has
    // positive weights, K and the true integral both lie in [Q_lo W, Q_hi W]
    // with W the panel's geometric cross-section and [Q_lo, Q_hi] the range Q
    // takes on the panel; the range is estimated from the rule's nodes (which
    // fall at unrelated phases of the ripple) and widened by half.  Panels
    // that matter are split until resolved; the rest keep this bound.
    // Beyond asymptotic_x the expansion of Q_ext is smooth: nothing to alias.
    const bool expansion_only = s_.asymptotic_x > 0 && k_ * std::exp(a) >= s_.asymptotic_x;
    if (p.x_span > resolved_x_span_ && !expansion_only)
      for (int c : layout_.checked()) {
        const double range = std::isfinite(p.q_hi[c] - p.q_lo[c]) ? p.q_hi[c] - p.q_lo[c] : 0.0;
        p.error[c] += 1.5 * range * std::abs(p.kronrod[kWeight]);
      }
    return p;
  }

  // A panel around a resolved resonance x0 - i gamma: the product rule of
  // pole_rule.hpp on F = f |x - x_p|^2 / x (the integrand f is per unit ln r,
  // du = dx / x), its 13-point sum as the coarse estimate, and a rounding
  // term: the weights grow like 1/gamma where F is small (F(x0) ~ |R|^2).
  Panel evaluate_pole(double a, double b, double x0, double gamma) const {
    throw_if_cancelled(s_.cancel);
    Panel p;
    p.a = a;
    p.b = b;
    p.pole = true;
    p.pole_x0 = x0;
    p.pole_gamma = gamma;
    const double xa = k_ * std::exp(a), xb = k_ * std::exp(b);
    const PoleRule rule = pole_rule(xa, xb, x0, gamma);
    std::vector<Node> nodes;
    std::vector<double> fine, coarse, jacobian;
    for (int j = 0; j < kPoleRulePoints; ++j) {
      const double x = rule.x[j];
      nodes.push_back(node(std::log(x / k_), p));
      const double factor = ((x - x0) * (x - x0) + gamma * gamma) / x;
      fine.push_back(rule.fine[j] * factor);
      coarse.push_back(rule.coarse[j] * factor);
    }
    accumulate(p, nodes, fine, coarse, fine);
    p.x_span = xb - xa;
    return p;
  }

  // Halves of a panel; a resonance's panel keeps its pole in the half (or
  // both halves) that hold x0, cutting at x0 itself when it lies well
  // inside, so that the pole is never just outside a panel whose rule does
  // not know it.
  std::pair<Panel, Panel> halves(const Panel& p) const {
    double cut = 0.5 * (p.a + p.b);
    if (!p.pole) return {evaluate(p.a, cut), evaluate(cut, p.b)};
    const double u0 = std::log(p.pole_x0 / k_), w = p.b - p.a;
    if (u0 > p.a + 0.2 * w && u0 < p.b - 0.2 * w) cut = u0;
    auto piece = [&](double a, double b) {
      const bool holds = u0 >= a && u0 <= b;
      return holds ? evaluate_pole(a, b, p.pole_x0, p.pole_gamma) : evaluate(a, b);
    };
    return {piece(p.a, cut), piece(cut, p.b)};
  }

  // Both halves of each panel, evaluated in parallel (TBB; each half is
  // independent).  The set of panels split is chosen before, so the result
  // does not depend on the number of threads.
  std::vector<Panel> split(const std::vector<Panel>& parents) const {
    std::vector<Panel> out(2 * parents.size());
    tbb::parallel_for(std::size_t(0), parents.size(), [&](std::size_t j) {
      auto [lower, upper] = halves(parents[j]);
      out[2 * j] = std::move(lower);
      out[2 * j + 1] = std::move(upper);
    });
    return out;
  }

  double wavenumber() const { return k_; }
  bool resonances() const { return resonances_; }

 private:
  // The sums of one panel from its nodes with the weights of its two rules
  // (`fine` its value, the difference from `coarse` its error), the range of
  // every component sampled, and with `rounding` weights the rounding term
  // 4 eps sum |w f|.
  void accumulate(Panel& p, const std::vector<Node>& nodes, const std::vector<double>& fine,
                  const std::vector<double>& coarse, const std::vector<double>& rounding) const {
    const int n = layout_.size();
    Vec k(n, 0.0), g(n, 0.0), r(n, 0.0);
    p.q_lo.assign(n, INFINITY);
    p.q_hi.assign(n, -INFINITY);
    p.q_max.assign(n, 0.0);
    std::vector<double> xs;
    for (const Node& nd : nodes)
      if (!nd.asymptotic) xs.push_back(nd.x);
    std::vector<Efficiency> eff(xs.size());
    if (!xs.empty()) q_(xs.data(), xs.size(), eff.data());
    std::size_t e = 0;
    const Efficiency none;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const Node& nd = nodes[j];
      double qext = 0;
      const Vec f = integrand(nd, nd.asymptotic ? none : eff[e++], qext);
      ++p.evaluations;
      p.qext_max = std::max(p.qext_max, std::abs(qext));
      for (int c = 0; c < n; ++c) {
        k[c] += fine[j] * f[c];
        g[c] += coarse[j] * f[c];
        if (!rounding.empty()) r[c] += std::abs(rounding[j] * f[c]);
        if (f[kWeight] > 0) {
          const double q = f[c] / f[kWeight];
          p.q_lo[c] = std::min(p.q_lo[c], q);
          p.q_hi[c] = std::max(p.q_hi[c], q);
          p.q_max[c] = std::max(p.q_max[c], std::abs(q));
        }
      }
    }
    p.kronrod = k;
    p.difference.assign(n, 0.0);
    p.error.assign(n, 0.0);
    for (int c = 0; c < n; ++c) {
      p.difference[c] = k[c] - g[c];
      p.error[c] = std::abs(k[c] - g[c]) + 4 * std::numeric_limits<double>::epsilon() * r[c];
    }
  }

  const SizeDistribution& d_;
  double k_;
  const EfficiencyBatch& q_;
  QuadratureSettings s_;
  Layout layout_;
  Rule rule_;
  bool resonances_;         // nearly lossless: resonances located, panels narrow in x
  double resolved_x_span_;  // x-width a panel may span and still trust |K - G|
  std::complex<double> m_;  // for the large-x bound
};

}  // namespace attenuvis::weather::detail
