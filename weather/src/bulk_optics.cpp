// Adaptive Gauss-Kronrod integration of efficiencies over a size distribution.
#include "attenuvis/weather/bulk_optics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include <tbb/parallel_for.h>

#include "attenuvis/io/check.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "resonance.hpp"
#include "bulk_components.hpp"
#include "extinction_tail.hpp"
#include "gauss_kronrod_rule.hpp"
#include "attenuvis/io/number_text.hpp"

namespace attenuvis::weather {
using io::significant;
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
using detail::kExt;
using detail::kSca;
using detail::kAbs;
using detail::kGSca;
using detail::kAsym;
using detail::kWeight;
using detail::kBack;
using detail::kFixed;
using detail::Layout;
using detail::Vec;

struct Panel {
  double a = 0, b = 0;  // in u = ln r
  Vec kronrod, error;
  Vec difference;       // signed K - G (without the aliasing term): errors of ratios
  Vec q_max;            // largest |component / weight| sampled (for the tails)
  double qext_max = 0;
  double x_span = 0;  // size-parameter width of the panel
  bool floor = false; // no wider than resonance_x_span: its error counted as resonance error
  std::size_t evaluations = 0;
  double max_x = 0;
  bool used_asymptotic = false;
};

using detail::Rule;
using detail::rule_for;

class Integrator {
 public:
  Integrator(const SizeDistribution& d, double wavelength, const EfficiencyBatch& q, const QuadratureSettings& s,
             std::complex<double> m)
      : d_(d), k_(2 * kPi / wavelength), q_(q), s_(s), layout_(s), rule_(rule_for(s.kronrod_points)),
        resolved_x_span_(0.6 * s.kronrod_points), m_(m) {}

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
    Node nd{k_ * r, r * d_.density(r) * kPi * r * r, false};
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
    f[kBack] = w * e.qback / (4 * kPi);
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
    double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    const int n = layout_.size();
    Vec k(n, 0.0), g(n, 0.0), q_min(n, INFINITY), q_max(n, -INFINITY);
    p.q_max.assign(n, 0.0);
    p.kronrod.assign(n, 0.0);
    p.error.assign(n, 0.0);
    p.difference.assign(n, 0.0);
    std::vector<Node> nodes;
    std::vector<double> xs;
    for (std::size_t i = 0; i < rule_.abscissa.size(); ++i)
      for (int sgn = 0; sgn < (i == 0 ? 1 : 2); ++sgn) {
        nodes.push_back(node(mid + (sgn ? -rule_.abscissa[i] : rule_.abscissa[i]) * half, p));
        nodes.back().rule = i;
        if (!nodes.back().asymptotic) xs.push_back(nodes.back().x);
      }
    std::vector<Efficiency> eff(xs.size());
    if (!xs.empty()) q_(xs.data(), xs.size(), eff.data());
    std::size_t e = 0;
    const Efficiency none;
    for (const Node& nd : nodes) {
      double qext = 0;
      Vec f = integrand(nd, nd.asymptotic ? none : eff[e++], qext);
      ++p.evaluations;
      p.qext_max = std::max(p.qext_max, std::abs(qext));
      for (int c = 0; c < n; ++c) {
        k[c] += rule_.kronrod_weight[nd.rule] * f[c];
        g[c] += rule_.gauss_weight[nd.rule] * f[c];
        if (f[kWeight] > 0) {
          double q = f[c] / f[kWeight];
          q_min[c] = std::min(q_min[c], q);
          q_max[c] = std::max(q_max[c], q);
          p.q_max[c] = std::max(p.q_max[c], std::abs(q));
        }
      }
    }
    for (int c = 0; c < n; ++c) {
      p.kronrod[c] = half * k[c];
      p.difference[c] = half * (k[c] - g[c]);
      p.error[c] = half * std::abs(k[c] - g[c]);
    }
    p.x_span = k_ * (std::exp(b) - std::exp(a));
    // |K - G| estimates the error only where the rule resolves the ripple of
    // Q(x) (period pi/(n-1) ~ 9.5 in x for water).  On a wider panel K and G
    // can alias alike.  There, since K has positive weights, K and the true
    // integral both lie in [Q_lo W, Q_hi W] with W the panel's geometric
    // cross-section and [Q_lo, Q_hi] the range Q takes on the panel; the
    // range is estimated from the rule's nodes (which fall at unrelated
    // phases of the ripple) and widened by half.  Panels that matter are
    // split until resolved; the rest keep this bound.
    if (p.x_span > resolved_x_span_)
      for (int c : layout_.checked()) {
        double range = std::isfinite(q_max[c] - q_min[c]) ? q_max[c] - q_min[c] : 0.0;
        p.error[c] += 1.5 * range * std::abs(p.kronrod[kWeight]);
      }
    return p;
  }

  // Both halves of each panel, evaluated in parallel (TBB; each half is
  // independent).  The set of panels split is chosen before, so the result
  // does not depend on the number of threads.
  std::vector<Panel> split(const std::vector<Panel>& parents) const {
    std::vector<Panel> halves(2 * parents.size());
    tbb::parallel_for(std::size_t(0), halves.size(), [&](std::size_t j) {
      const Panel& p = parents[j / 2];
      double mid = 0.5 * (p.a + p.b);
      halves[j] = (j % 2 == 0) ? evaluate(p.a, mid) : evaluate(mid, p.b);
    });
    return halves;
  }

 private:
  const SizeDistribution& d_;
  double k_;
  const EfficiencyBatch& q_;
  QuadratureSettings s_;
  Layout layout_;
  Rule rule_;
  double resolved_x_span_;  // x-width a panel may span and still trust |K - G|
  std::complex<double> m_;  // for the large-x bound
};

// The r^2 support of `d` (where the geometric cross-section lives), all but
// `tail_fraction` of it; throws when the moment diverges or is empty.
Support cross_section_support(const SizeDistribution& d, double tail_fraction) {
  Support support;
  try {
    support = d.support(2.0, tail_fraction);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("sigma_ext integral diverges: ") + e.what());
  }
  if (!(support.total_moment > 0) || !std::isfinite(support.total_moment))
    throw std::runtime_error("sigma_ext integral diverges or is empty: the geometric cross-section moment "
                             "int r^2 n(r) dr is " + significant(support.total_moment, 3));
  return support;
}

// Initial panels: the support's smooth pieces in ln r, each cut into steps
// of at most 0.25 in ln r and at the asymptotic switch, so the first pass
// already sees the shape of the weight.
std::vector<Panel> initial_panels(const Integrator& integ, const Support& support, const QuadratureSettings& s,
                                  double k) {
  std::vector<double> cuts;
  for (std::size_t i = 0; i + 1 < support.breakpoints_m.size(); ++i) {
    double a = std::log(support.breakpoints_m[i]), b = std::log(support.breakpoints_m[i + 1]);
    int pieces = std::max(1, static_cast<int>(std::ceil((b - a) / 0.25)));
    for (int j = 0; j < pieces; ++j) cuts.push_back(a + (b - a) * j / pieces);
    if (i + 2 == support.breakpoints_m.size()) cuts.push_back(b);
  }
  if (s.asymptotic_x > 0) cuts.push_back(std::log(s.asymptotic_x / k));
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  double u_lo = std::log(support.breakpoints_m.front()), u_hi = std::log(support.breakpoints_m.back());

  std::vector<std::pair<double, double>> first;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i] >= u_lo && cuts[i + 1] <= u_hi) first.emplace_back(cuts[i], cuts[i + 1]);
  std::vector<Panel> panels(first.size());
  tbb::parallel_for(std::size_t(0), first.size(),
                    [&](std::size_t i) { panels[i] = integ.evaluate(first[i].first, first[i].second); });
  return panels;
}

// The panels of the integral and their running sums, refined adaptively.
//
// Nearly non-absorbing spheres (resonance.hpp): a panel no wider than
// resonance_x_span in x resolves the smooth ripple of Q(x) (period ~0.8 in x
// for water), so what its Kronrod and Gauss sums still disagree on is
// resonance structure; it is reported as resonance error (floor_error), not
// counted against rel_tolerance.
class Refinement {
 public:
  Refinement(const Integrator& integ, std::vector<Panel> panels, const QuadratureSettings& s)
      : integ_(integ), s_(s), layout_(integ.layout()), checked_(layout_.checked()),
        resonances_(s.estimate_resonances), panels_(std::move(panels)) {
    const std::size_t n = static_cast<std::size_t>(layout_.size());
    value_.assign(n, 0.0);
    error_.assign(n, 0.0);
    floor_error_.assign(n, 0.0);
    scale0_.assign(n, 0.0);
    for (auto& p : panels_) p.floor = is_floor(p);
    for (const auto& p : panels_) evaluations_ += p.evaluations;
    totals();
    for (int c : checked_) scale0_[c] = scale(c, value_);
  }

  // Recomputes the sums from the panels (the running sums drift).
  void totals() {
    std::fill(value_.begin(), value_.end(), 0.0);
    std::fill(error_.begin(), error_.end(), 0.0);
    std::fill(floor_error_.begin(), floor_error_.end(), 0.0);
    for (const auto& p : panels_)
      for (std::size_t c = 0; c < value_.size(); ++c) {
        value_[c] += p.kronrod[c];
        (p.floor ? floor_error_ : error_)[c] += p.error[c];
      }
  }

  // Each component's error is measured against the scale it is reported on
  // (Layout::scale).  Resonance errors of the optional (angular) components
  // have their own target, angular_resonance_tolerance.
  double scale(int c, const Vec& v) const { return layout_.scale(c, v); }
  bool within(const Vec& e, double tol, double angular_tol) const {
    for (int c : checked_)
      if (e[c] > (layout_.angular(c) ? angular_tol : tol) * scale(c, value_)) return false;
    return true;
  }
  bool quadrature_met() const { return within(error_, s_.rel_tolerance, s_.rel_tolerance); }

  // Global adaptive refinement (QUADPACK QAG-style), the worst panels first,
  // kBatch at a time so that their halves can be evaluated in parallel.
  // Pass 1 (floor_pass false) splits the panels wider than the resonance
  // floor until their summed error meets rel_tolerance; pass 2 splits floor
  // panels (down to min_resonance_x_span) until the resonance error meets
  // resonance_tolerance, or the evaluation budget is spent.  Pass 2 is what
  // finds and resolves the resonances of intermediate width (1e-2..1 in x)
  // that carry most of the resonance error; narrower ones stay reported.
  void refine(bool floor_pass) {
    auto cmp = [&](std::size_t i, std::size_t j) {
      return floor_pass ? floor_key(panels_[i]) < floor_key(panels_[j]) : key(panels_[i]) < key(panels_[j]);
    };
    std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(cmp)> heap(cmp);
    for (std::size_t i = 0; i < panels_.size(); ++i)
      if (panels_[i].floor == floor_pass) heap.push(i);
    std::size_t rounds = 0;
    for (;;) {
      bool done = floor_pass ? within(floor_error_, s_.resonance_tolerance, s_.angular_resonance_tolerance)
                             : quadrature_met();
      if (done || heap.empty() || evaluations_ > s_.max_evaluations) return;
      std::vector<std::size_t> chosen;
      std::vector<Panel> parents;
      while (!heap.empty() && chosen.size() < kBatch) {
        std::size_t i = heap.top();
        heap.pop();
        const Panel& p = panels_[i];
        double mid = 0.5 * (p.a + p.b);
        if (!(mid > p.a && mid < p.b) || (p.b - p.a) < 1e-12) continue;  // cannot split further
        if (floor_pass && 0.5 * p.x_span < s_.min_resonance_x_span) continue;  // narrower than any sampling
        chosen.push_back(i);
        parents.push_back(p);
      }
      if (chosen.empty()) return;
      std::vector<Panel> halves = integ_.split(parents);
      for (std::size_t j = 0; j < chosen.size(); ++j) {
        replace_by_halves(chosen[j], parents[j], halves[2 * j], halves[2 * j + 1]);
        for (std::size_t child : {chosen[j], panels_.size() - 1})
          if (panels_[child].floor == floor_pass) heap.push(child);
      }
      if (++rounds % 32 == 0) totals();  // keep the running sums from drifting
    }
  }

  // Throws naming the worst integral when pass 1 did not meet rel_tolerance
  // (a sum that is not finite, which no comparison catches, included).
  void require_quadrature_met(const SizeDistribution& d) const {
    for (int c : checked_)
      if (!std::isfinite(value_[c]) || !std::isfinite(error_[c]))
        throw std::runtime_error("integral over " + d.describe() + " is not finite in double precision (sigma_ext " +
                                 significant(value_[kExt], 3) + "); the distribution's number density is out of "
                                 "range");
    if (quadrature_met()) return;
    int worst = kExt;
    double ratio = 0;
    for (int c : checked_)
      if (error_[c] / scale(c, value_) > ratio) { ratio = error_[c] / scale(c, value_); worst = c; }
    throw std::runtime_error(component_name(worst) + " integral over " + d.describe() + ": relative tolerance " +
                             significant(s_.rel_tolerance, 3) + " not met after " + std::to_string(evaluations_) +
                             " efficiency evaluations (estimated quadrature error " + significant(ratio, 3) +
                             " relative); the integrand is too rough or too wide for the evaluation budget "
                             "(raise max_evaluations or the tolerance)");
  }

  const std::vector<Panel>& panels() const { return panels_; }
  const Vec& value() const { return value_; }
  const Vec& error() const { return error_; }
  const Vec& floor_error() const { return floor_error_; }
  const Layout& layout() const { return layout_; }
  std::size_t evaluations() const { return evaluations_; }

 private:
  static constexpr std::size_t kBatch = 8;

  bool is_floor(const Panel& p) const { return resonances_ && p.x_span <= s_.resonance_x_span; }
  // Pass 1 order: the worst relative error first.
  double key(const Panel& p) const {
    double worst = 0;
    for (int c : checked_) worst = std::max(worst, p.error[c] / scale0_[c]);
    return worst;
  }
  // The integral of a component the tolerances govern (Layout::checked), by
  // its constant (bulk_components.hpp), not by its position among them.
  std::string component_name(int c) const {
    switch (c) {
      case kExt: return "sigma_ext";
      case kSca: return "sigma_sca";
      case kAbs: return "sigma_abs";
      case kGSca: return "asymmetry g";
      case kBack: return "backscatter beta_pi";
      default: break;
    }
    ATTENUVIS_CHECK_GE(c, kFixed);  // kAsym and kWeight are never checked
    ATTENUVIS_CHECK_LT(c, layout_.size());
    const int angle = c - layout_.angle(0), part = c - layout_.expansion_at(0);
    if (c < layout_.angle(0)) return "Legendre moment chi_" + std::to_string(c - kFixed);
    if (c < layout_.expansion_at(0)) return "phase function at " + significant(s_.angles_deg[angle], 6) + " deg";
    return std::string("scattering-matrix expansion ") + detail::kExpansionPartNames[part / layout_.moments] + "_" +
           std::to_string(part % layout_.moments);
  }
  // In pass 2 the order must not depend on what the nodes sampled: splitting
  // where |K - G| is large splits away the nodes that hit a resonance while
  // panels whose nodes missed theirs stay, which biases sigma low (measured
  // for advection fog at 550 nm: 0.0287462 +- 2.9e-7 with that order against
  // 0.0287466 +- 0.9e-7 at a tighter target, intervals that do not overlap).
  // Floor panels are therefore split by a key that follows the weight alone:
  // their geometric cross-section W times their width in x (a hit resonance
  // costs of order W x_span / span of Q), divided by the size parameter,
  // since a Mie evaluation costs ~x (split where error goes cheapest).
  static double floor_key(const Panel& p) {
    double x_mid = p.x_span / (2 * std::sinh(0.5 * (p.b - p.a)));
    return std::abs(p.kronrod[kWeight]) * p.x_span / std::max(x_mid, 1.0);
  }
  // panels_[i] (= parent) becomes `lower`; `upper` joins at the end.
  void replace_by_halves(std::size_t i, const Panel& parent, Panel& lower, Panel& upper) {
    for (Panel* child : {&lower, &upper}) {
      child->floor = is_floor(*child);
      evaluations_ += child->evaluations;
      for (std::size_t c = 0; c < value_.size(); ++c) {
        value_[c] += child->kronrod[c];
        (child->floor ? floor_error_ : error_)[c] += child->error[c];
      }
    }
    for (std::size_t c = 0; c < value_.size(); ++c) {
      value_[c] -= parent.kronrod[c];
      (parent.floor ? floor_error_ : error_)[c] -= parent.error[c];
    }
    panels_[i] = lower;
    panels_.push_back(upper);
  }

  const Integrator& integ_;
  const QuadratureSettings& s_;
  const Layout& layout_;
  std::vector<int> checked_;
  bool resonances_;
  std::vector<Panel> panels_;
  Vec value_, error_, floor_error_, scale0_;
  std::size_t evaluations_ = 0;
};

// Largest |component / weight| sampled on any panel: the tail bound of an
// optional component is twice that times pi times the omitted r^2 moment
// (as extinction_tail_bound, without the floor of 4 that Q_ext alone obeys).
double sampled_max(const Refinement& r, int c) {
  double m = 0;
  for (const auto& p : r.panels()) m = std::max(m, p.q_max[c]);
  return m;
}

// Component c as an IntegralEstimate with all its error terms.
IntegralEstimate component_estimate(const Refinement& r, int c, double omitted_moment, bool resonances) {
  IntegralEstimate e;
  e.value = r.value()[c];
  e.quadrature_error = r.error()[c];
  e.tail_error = 2 * sampled_max(r, c) * kPi * omitted_moment;
  if (resonances) e.resonance_error = r.floor_error()[c];
  return e;
}

// beta_pi, the lidar ratio, chi_l and p(theta), each normalised quantity
// (v = num/sigma_sca) with error (err_num + |v| err_sca) / sigma_sca.
void fill_optional(BulkOptics& out, const Refinement& r, const Support& support, const QuadratureSettings& s) {
  const Layout& layout = r.layout();
  const double sca = out.scattering.value;
  if (!out.scattering_computed || !(sca > 0)) return;
  if (layout.back) {
    out.backscatter_computed = true;
    out.backscatter = component_estimate(r, kBack, support.omitted_moment, s.estimate_resonances);
    const double beta = out.backscatter.value;
    if (beta > 0) {
      out.lidar_ratio = out.extinction.value / beta;
      out.lidar_ratio_error =
          out.lidar_ratio * (out.extinction.error() / out.extinction.value + out.backscatter.error() / beta);
    }
  }
  // v = M_c / sigma_sca from the same panels: its error is that of
  // M_c - v sigma_sca, whose Kronrod-Gauss differences cancel where the two
  // sums err alike (a resonance hit by a node raises both), panel by panel;
  // the aliasing terms of wide panels are added as they are.
  auto normalised = [&](int c, double& value, double& error) {
    value = r.value()[c] / sca;
    double sum = 0;
    for (const auto& p : r.panels()) {
      const double aliasing_c = p.error[c] - std::abs(p.difference[c]);
      const double aliasing_sca = p.error[kSca] - std::abs(p.difference[kSca]);
      sum += std::abs(p.difference[c] - value * p.difference[kSca]) + aliasing_c + std::abs(value) * aliasing_sca;
    }
    const double tails = 2 * (sampled_max(r, c) + std::abs(value) * sampled_max(r, kSca)) * kPi * support.omitted_moment;
    error = (sum + tails) / sca;
  };
  out.moments.assign(layout.moments, 0.0);
  out.moments_error.assign(layout.moments, 0.0);
  for (int l = 0; l < layout.moments; ++l) normalised(layout.moment(l), out.moments[l], out.moments_error[l]);
  out.angles_deg = s.angles_deg;
  out.phase.assign(layout.angles, 0.0);
  out.phase_error.assign(layout.angles, 0.0);
  for (int j = 0; j < layout.angles; ++j) normalised(layout.angle(j), out.phase[j], out.phase_error[j]);
  if (layout.expansion > 0) {
    const auto values = detail::expansion_parts(out.expansion);
    const auto errors = detail::expansion_parts(out.expansion_error);
    ATTENUVIS_CHECK_EQ(layout.expansion, detail::kExpansionParts * layout.moments);
    for (int k = 0; k < detail::kExpansionParts; ++k) {
      values[k]->assign(layout.moments, 0.0);
      errors[k]->assign(layout.moments, 0.0);
      for (int l = 0; l < layout.moments; ++l)
        normalised(layout.expansion_at(k * layout.moments + l), (*values[k])[l], (*errors[k])[l]);
    }
  }
}

// The estimates, errors and method of the refined panels.
BulkOptics bulk_optics_result(const Refinement& r, const Support& support, const QuadratureSettings& s,
                              double tail_fraction) {
  const Vec& value = r.value();
  const Vec& error = r.error();
  BulkOptics out;
  out.evaluations = r.evaluations();
  bool used_asymptotic = false;
  double qext_max = 0;
  for (const auto& p : r.panels()) {
    qext_max = std::max(qext_max, p.qext_max);
    out.max_size_parameter = std::max(out.max_size_parameter, p.max_x);
    used_asymptotic = used_asymptotic || p.used_asymptotic;
  }
  out.scattering_computed = !used_asymptotic;
  const double tail = detail::extinction_tail_bound(qext_max, support.omitted_moment);

  auto fill = [&](IntegralEstimate& e, int c) {
    e.value = value[c];
    e.quadrature_error = error[c];
    e.tail_error = tail;
  };
  fill(out.extinction, kExt);
  fill(out.scattering, kSca);
  fill(out.absorption, kAbs);
  out.extinction.asymptotic_error = value[kAsym] + error[kAsym];
  if (s.estimate_resonances) {
    out.extinction.resonance_error = r.floor_error()[kExt];
    out.scattering.resonance_error = r.floor_error()[kSca];
    out.absorption.resonance_error = r.floor_error()[kAbs];
    out.floor_panels = 0;
    for (const auto& p : r.panels()) out.floor_panels += p.floor ? 1 : 0;
  }
  if (out.scattering_computed && value[kExt] > 0) {
    out.albedo = value[kSca] / value[kExt];
    out.albedo_error = (out.scattering.error() + out.albedo * out.extinction.error()) / value[kExt];
    out.asymmetry = value[kSca] > 0 ? value[kGSca] / value[kSca] : 0;
    out.asymmetry_error = value[kSca] > 0 ? (error[kGSca] + tail + std::abs(out.asymmetry) * out.scattering.error()) /
                                                value[kSca]
                                          : 0;
  }
  fill_optional(out, r, support, s);
  std::ostringstream method;
  method << "adaptive Gauss-Kronrod " << s.kronrod_points << " (Boost.Math) in ln r, rel. tol " << s.rel_tolerance
         << ", tails cut at " << tail_fraction << " of the r^2 moment, " << out.evaluations << " evaluations, x <= "
         << significant(out.max_size_parameter, 3);
  if (used_asymptotic) method << ", Q_ext large-x expansion beyond x = " << s.asymptotic_x;
  if (s.estimate_resonances)
    method << ", resonance panels <= " << s.resonance_x_span << " in x refined to " << s.resonance_tolerance
           << " relative (down to " << s.min_resonance_x_span << " in x)";
  if (s.estimate_resonances && (r.layout().back || r.layout().size() > kFixed))
    method << ", " << s.angular_resonance_tolerance << " for backscatter/angular quantities";
  out.method = method.str();
  return out;
}

BulkOptics integrate_bulk_optics_impl(const SizeDistribution& d, double wavelength, const EfficiencyBatch& q,
                                      const QuadratureSettings& s, std::complex<double> m) {
  if (!(wavelength > 0)) throw std::invalid_argument("wavelength must be > 0");
  if (!(s.rel_tolerance > 0 && s.rel_tolerance < 1)) throw std::invalid_argument("rel_tolerance must lie in (0, 1)");
  const double tail_fraction = s.tail_fraction > 0 ? s.tail_fraction : 1e-3 * s.rel_tolerance;
  const Support support = cross_section_support(d, tail_fraction);
  const Integrator integ(d, wavelength, q, s, m);
  Refinement r(integ, initial_panels(integ, support, s, 2 * kPi / wavelength), s);
  r.refine(false);
  r.totals();
  r.require_quadrature_met(d);
  if (s.estimate_resonances) {
    r.refine(true);
    r.totals();
  }
  return bulk_optics_result(r, support, s, tail_fraction);
}

}  // namespace

BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyBatch& q,
                                 const QuadratureSettings& s, std::complex<double> m) {
  QuadratureSettings t = s;
  if (m.imag() >= resonance_free_k()) t.estimate_resonances = false;
  return integrate_bulk_optics_impl(d, wavelength_m, q, t, m);
}

BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyFunction& q,
                                 const QuadratureSettings& s, std::complex<double> m) {
  const EfficiencyBatch one_by_one = [&q](const double* x, std::size_t n, Efficiency* out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = q(x[i]);
  };
  return integrate_bulk_optics(d, wavelength_m, one_by_one, s, m);
}

}  // namespace attenuvis::weather
