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
#include "bulk_panels.hpp"
#include "resonance_plan.hpp"
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
using detail::Panel;
using detail::Integrator;

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
std::vector<double> initial_cuts(const Support& support, const QuadratureSettings& s, double k) {
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
  const double u_lo = std::log(support.breakpoints_m.front()), u_hi = std::log(support.breakpoints_m.back());
  cuts.erase(std::remove_if(cuts.begin(), cuts.end(), [&](double u) { return u < u_lo || u > u_hi; }), cuts.end());
  return cuts;
}

// An interval to evaluate, with the resolved resonance it holds (if any).
struct Task {
  double a = 0, b = 0;
  const detail::ResolvedResonance* pole = nullptr;
};

std::vector<Panel> evaluate_tasks(const Integrator& integ, const std::vector<Task>& tasks) {
  std::vector<Panel> panels(tasks.size());
  tbb::parallel_for(std::size_t(0), tasks.size(), [&](std::size_t i) {
    const Task& t = tasks[i];
    panels[i] = t.pole ? integ.evaluate_pole(t.a, t.b, t.pole->resonance.pole.real(), t.pole->resonance.half_width())
                       : integ.evaluate(t.a, t.b);
  });
  return panels;
}

std::vector<Task> plain_tasks(const std::vector<double>& cuts) {
  std::vector<Task> tasks;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) tasks.push_back({cuts[i], cuts[i + 1], nullptr});
  return tasks;
}

// The cuts with a panel [x0 - reach, x0 + reach] for every resolved
// resonance: the cuts inside it are dropped (the support's breakpoints never
// are: reach stops at them, resonance_plan.cpp).
std::vector<Task> tasks_with_resonances(const std::vector<double>& cuts, const detail::ResonancePlan& plan,
                                        double k) {
  std::vector<Task> tasks;
  std::size_t i = 0;
  double at = cuts.front();
  for (const auto& r : plan.resolved) {
    const double lo = std::log((r.resonance.pole.real() - r.reach) / k);
    const double hi = std::log((r.resonance.pole.real() + r.reach) / k);
    for (; i < cuts.size() && cuts[i] <= lo; ++i)
      if (cuts[i] > at) tasks.push_back({at, cuts[i], nullptr}), at = cuts[i];
    if (lo > at) tasks.push_back({at, lo, nullptr});
    tasks.push_back({lo, hi, &r});
    at = hi;
    while (i < cuts.size() && cuts[i] <= hi) ++i;
  }
  for (; i < cuts.size(); ++i)
    if (cuts[i] > at) tasks.push_back({at, cuts[i], nullptr}), at = cuts[i];
  return tasks;
}

// Each component's tolerance: rel_tolerance on sigma_ext, sigma_sca,
// sigma_abs; the angular tolerance (QuadratureSettings::angular_tolerance) on
// g, beta_pi, chi_l, p(theta) and the expansion.
double component_tolerance(const Layout& layout, int c, const QuadratureSettings& s) {
  return (c == kGSca || layout.angular(c)) ? detail::angular_tolerance(s) : s.rel_tolerance;
}

// The panels of the integral and their running sums, refined adaptively
// (QUADPACK QAG-style, the worst panels first, kBatch at a time so that
// their halves are evaluated in parallel) until every component's
// quadrature error plus the bound on its unresolved resonances meets its
// tolerance times its scale (Layout::scale).
class Refinement {
 public:
  // extinction_only: the large-x expansion was used, so sigma_ext alone is
  // reported (BulkOptics::scattering_computed) and alone governs the refinement.
  Refinement(const Integrator& integ, std::vector<Panel> panels, const QuadratureSettings& s, Vec unresolved,
             bool extinction_only)
      : integ_(integ), s_(s), layout_(integ.layout()),
        checked_(extinction_only ? std::vector<int>{kExt} : layout_.checked()), panels_(std::move(panels)),
        unresolved_(std::move(unresolved)) {
    const std::size_t n = static_cast<std::size_t>(layout_.size());
    if (unresolved_.empty()) unresolved_.assign(n, 0.0);
    ATTENUVIS_CHECK_EQ(unresolved_.size(), n);
    value_.assign(n, 0.0);
    error_.assign(n, 0.0);
    for (const auto& p : panels_) evaluations_ += p.evaluations;
    totals();
    scale0_.assign(n, 0.0);
    for (int c : checked_) scale0_[c] = scale(c) * component_tolerance(layout_, c, s_);
  }

  // Recomputes the sums from the panels (the running sums drift).
  void totals() {
    std::fill(value_.begin(), value_.end(), 0.0);
    std::fill(error_.begin(), error_.end(), 0.0);
    for (const auto& p : panels_)
      for (std::size_t c = 0; c < value_.size(); ++c) {
        value_[c] += p.kronrod[c];
        error_[c] += p.error[c];
      }
  }

  double scale(int c) const { return layout_.scale(c, value_); }

  // The error of the quantity component c is reported as, relative to its
  // tolerance times its scale: sigma_ext, sigma_sca and sigma_abs each get
  // 0.45 of rel_tolerance x sigma_ext (so that the albedo, (err_sca + w
  // err_ext) / sigma_ext, stays within it too); the ratios to sigma_sca (g,
  // chi_l, p(theta), the expansion) carry (err_c + |v| err_sca) / sigma_sca
  // as fill_optional reports them, against Layout::scale (relative to |v|
  // for p(theta), to max(|v|, Layout::kMomentFloor) for chi_l); beta_pi
  // carries its own relative error plus sigma_ext's, so that the lidar ratio
  // stays within its tolerance.
  // 0.9 of each leaves room for the tails (1e-3 of the tolerance).
  // With quadrature false, the share of the unresolved resonances alone.
  double share(int c, bool quadrature = true) const {
    const double tol = component_tolerance(layout_, c, s_);
    const auto err = [&](int i) { return (quadrature ? error_[i] : 0.0) + unresolved_[i]; };
    const double ext = std::max(std::abs(value_[kExt]), 1e-300), sca = std::max(std::abs(value_[kSca]), 1e-300);
    if (c == kExt || c == kSca || c == kAbs) return err(c) / (0.45 * tol * ext);
    if (c == kBack) return (err(c) / std::max(std::abs(value_[c]), 1e-300) + err(kExt) / ext) / (0.9 * tol);
    const double v = value_[c] / sca;
    return (err(c) + std::abs(v) * err(kSca)) / (0.9 * tol * scale(c));
  }
  bool met() const {
    for (int c : checked_)
      if (share(c) > 1) return false;
    return true;
  }
  // Met, or beyond reach: where the budget left resonances unresolved whose
  // bounds alone take more than half of a component's tolerance (the plan's
  // share is 0.4), refining its quadrature error below those bounds buys
  // nothing, so the refinement stops there (share is linear in the error
  // terms: share <= 2 x the resonances' share means quadrature <= resonances).
  bool settled() const {
    for (int c : checked_) {
      const double resonances = share(c, false);
      if (share(c) > 1 && !(resonances > 0.5 && share(c) <= 2 * resonances)) return false;
    }
    return true;
  }

  void refine() {
    auto cmp = [&](std::size_t i, std::size_t j) { return key(panels_[i]) < key(panels_[j]); };
    std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(cmp)> heap(cmp);
    for (std::size_t i = 0; i < panels_.size(); ++i) heap.push(i);
    std::size_t rounds = 0;
    for (;;) {
      if (settled() || heap.empty() || evaluations_ > s_.max_evaluations) return;
      std::vector<std::size_t> chosen;
      std::vector<Panel> parents;
      while (!heap.empty() && chosen.size() < kBatch) {
        const std::size_t i = heap.top();
        heap.pop();
        const Panel& p = panels_[i];
        const double mid = 0.5 * (p.a + p.b);
        if (!(mid > p.a && mid < p.b) || (p.b - p.a) < 1e-12) continue;  // cannot split further
        chosen.push_back(i);
        parents.push_back(p);
      }
      if (chosen.empty()) return;
      std::vector<Panel> halves = integ_.split(parents);
      for (std::size_t j = 0; j < chosen.size(); ++j) {
        replace_by_halves(chosen[j], parents[j], halves[2 * j], halves[2 * j + 1]);
        heap.push(chosen[j]);
        heap.push(panels_.size() - 1);
      }
      if (++rounds % 32 == 0) totals();  // keep the running sums from drifting
    }
  }

  // Throws naming the worst integral when the tolerances are not met (a sum
  // that is not finite, which no comparison catches, included).  With
  // may_fall_short (nearly lossless spheres, bulk_optics.hpp) a finite result
  // that misses its tolerance is returned, and this says by how much.
  std::string require_met(const SizeDistribution& d, bool may_fall_short) const {
    for (int c : checked_)
      if (!std::isfinite(value_[c]) || !std::isfinite(error_[c]))
        throw std::runtime_error("integral over " + d.describe() + " is not finite in double precision (sigma_ext " +
                                 significant(value_[kExt], 3) + "); the distribution's number density is out of "
                                 "range");
    if (met()) return {};
    int worst = kExt;
    double ratio = 0;
    for (int c : checked_)
      if (share(c) > ratio) ratio = share(c), worst = c;
    const double tol = component_tolerance(layout_, worst, s_);
    if (may_fall_short)
      return component_name(worst) + ": relative tolerance " + significant(tol, 3) + " not met within " +
             std::to_string(evaluations_) + " efficiency evaluations (error reached " + significant(ratio, 3) +
             " times that, as reported) over " + d.describe();
    throw std::runtime_error(component_name(worst) + " integral over " + d.describe() + ": relative tolerance " +
                             significant(tol, 3) + " not met after " + std::to_string(evaluations_) +
                             " efficiency evaluations (estimated error " + significant(ratio, 3) +
                             " times that); the integrand is too rough or too wide for the evaluation budget "
                             "(raise max_evaluations or the tolerance)");
  }

  const std::vector<Panel>& panels() const { return panels_; }
  const Vec& value() const { return value_; }
  const Vec& error() const { return error_; }
  const Vec& unresolved() const { return unresolved_; }
  const Layout& layout() const { return layout_; }
  std::size_t evaluations() const { return evaluations_; }

 private:
  static constexpr std::size_t kBatch = 8;

  // The worst error relative to what its component may carry.
  double key(const Panel& p) const {
    double worst = 0;
    for (int c : checked_) worst = std::max(worst, p.error[c] / std::max(scale0_[c], 1e-300));
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
  // panels_[i] (= parent) becomes `lower`; `upper` joins at the end.
  void replace_by_halves(std::size_t i, const Panel& parent, Panel& lower, Panel& upper) {
    for (Panel* child : {&lower, &upper}) {
      evaluations_ += child->evaluations;
      for (std::size_t c = 0; c < value_.size(); ++c) {
        value_[c] += child->kronrod[c];
        error_[c] += child->error[c];
      }
    }
    for (std::size_t c = 0; c < value_.size(); ++c) {
      value_[c] -= parent.kronrod[c];
      error_[c] -= parent.error[c];
    }
    panels_[i] = lower;
    panels_.push_back(upper);
  }

  const Integrator& integ_;
  const QuadratureSettings& s_;
  const Layout& layout_;
  std::vector<int> checked_;
  std::vector<Panel> panels_;
  Vec unresolved_;
  Vec value_, error_, scale0_;
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
IntegralEstimate component_estimate(const Refinement& r, int c, double omitted_moment) {
  IntegralEstimate e;
  e.value = r.value()[c];
  e.quadrature_error = r.error()[c];
  e.tail_error = 2 * sampled_max(r, c) * kPi * omitted_moment;
  e.resonance_error = r.unresolved()[c];
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
    out.backscatter = component_estimate(r, kBack, support.omitted_moment);
    const double beta = out.backscatter.value;
    if (beta > 0) {
      out.lidar_ratio = out.extinction.value / beta;
      out.lidar_ratio_error =
          out.lidar_ratio * (out.extinction.error() / out.extinction.value + out.backscatter.error() / beta);
    }
  }
  // v = M_c / sigma_sca from the same panels: its error is that of
  // M_c - v sigma_sca, whose Kronrod-Gauss differences cancel where the two
  // sums err alike (a node near a resonance raises both), panel by panel;
  // the aliasing and rounding terms of panels are added as they are, and the
  // bounds on unresolved resonances of both.
  auto normalised = [&](int c, double& value, double& error) {
    value = r.value()[c] / sca;
    double sum = 0;
    for (const auto& p : r.panels()) {
      const double extra_c = p.error[c] - std::abs(p.difference[c]);
      const double extra_sca = p.error[kSca] - std::abs(p.difference[kSca]);
      sum += std::abs(p.difference[c] - value * p.difference[kSca]) + extra_c + std::abs(value) * extra_sca;
    }
    const double tails = 2 * (sampled_max(r, c) + std::abs(value) * sampled_max(r, kSca)) * kPi * support.omitted_moment;
    const double resonances = r.unresolved()[c] + std::abs(value) * r.unresolved()[kSca];
    error = (sum + tails + resonances) / sca;
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
                              double tail_fraction, const detail::ResonancePlan& plan) {
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
    e.resonance_error = r.unresolved()[c];
  };
  fill(out.extinction, kExt);
  fill(out.scattering, kSca);
  fill(out.absorption, kAbs);
  out.extinction.asymptotic_error = value[kAsym] + error[kAsym];
  out.resonances_resolved = plan.resolved.size();
  out.resonances_located = plan.located;
  if (out.scattering_computed && value[kExt] > 0) {
    out.albedo = value[kSca] / value[kExt];
    out.albedo_error = (out.scattering.error() + out.albedo * out.extinction.error()) / value[kExt];
    out.asymmetry = value[kSca] > 0 ? value[kGSca] / value[kSca] : 0;
    out.asymmetry_error = value[kSca] > 0 ? (error[kGSca] + r.unresolved()[kGSca] + tail +
                                             std::abs(out.asymmetry) * out.scattering.error()) / value[kSca]
                                          : 0;
  }
  fill_optional(out, r, support, s);
  std::ostringstream method;
  method << "adaptive Gauss-Kronrod " << s.kronrod_points << " (Boost.Math) in ln r, rel. tol " << s.rel_tolerance
         << " (" << detail::angular_tolerance(s) << " for g, backscatter and angular quantities)";
  method << ", tails cut at " << tail_fraction << " of the r^2 moment, " << out.evaluations << " evaluations, x <= "
         << significant(out.max_size_parameter, 3);
  if (used_asymptotic) method << ", Q_ext large-x expansion beyond x = " << s.asymptotic_x;
  if (s.estimate_resonances)
    method << ", resonances: " << plan.bracketed << " bracketed, " << plan.located << " located, "
           << plan.resolved.size() << " resolved by product-rule panels, the rest bounded (resonance_plan.hpp)";
  out.method = method.str();
  return out;
}

// What the first pass sampled near x0: the panel holding x0 and the largest
// size weight within x0 +- 1/2.
detail::NearbySamples nearby(const std::vector<Panel>& panels, const SizeDistribution& d, double k, double x0) {
  detail::NearbySamples near;
  const double u0 = std::log(x0 / k);
  for (const auto& p : panels)
    if (u0 >= p.a && u0 <= p.b) near.q_max = p.q_max;
  if (near.q_max.empty()) near.q_max.assign(panels.front().q_max.size(), 0.0);
  for (double x : {x0 - 0.5, x0, x0 + 0.5}) {
    const double r = x / k;
    if (r > 0) near.weight_x = std::max(near.weight_x, kPi * r * r * d.density(r) / k);
  }
  return near;
}

// The plan of the resonances of nearly lossless spheres (resonance_plan.hpp)
// from the first pass's panels: each component may carry its tolerance
// times its first estimate.  Resonance panels may take half the evaluation
// budget, each counted with the Gauss-Kronrod panel it cuts off beside it;
// the refinement needs the rest, at least to bring every panel to 2 in x
// (bulk_panels.hpp: wider, the nodes miss the resonances of half-width
// >= 0.1 that the plan leaves to them, and a component that is small away
// from its peaks, as a lossless sphere's Q_abs, is not bounded by its
// sampled range).
detail::ResonancePlan resonance_plan(const Integrator& integ, const std::vector<Panel>& first, const Support& support,
                                     const SizeDistribution& d, const QuadratureSettings& s, std::complex<double> m,
                                     bool extinction_only) {
  if (!s.estimate_resonances) return {};
  const Layout& layout = integ.layout();
  Vec value(static_cast<std::size_t>(layout.size()), 0.0), allowed(value.size(), 0.0);
  for (const auto& p : first)
    for (std::size_t c = 0; c < value.size(); ++c) value[c] += p.kronrod[c];
  // Resonances may take up to half of this (resonance_plan.hpp), a fifth of
  // what Refinement::share allows each quantity.
  for (int c : layout.checked())
    if (!extinction_only || c == kExt) allowed[c] = 0.4 * component_tolerance(layout, c, s) * layout.scale(c, value);
  const double k = integ.wavenumber();
  std::vector<double> breakpoints_x;
  for (double r : support.breakpoints_m) breakpoints_x.push_back(k * r);
  double x_hi = breakpoints_x.back();
  if (s.asymptotic_x > 0 && s.asymptotic_x < x_hi) {
    x_hi = s.asymptotic_x;
    breakpoints_x.push_back(x_hi);  // a cut of the first panels: no resonance panel crosses it
  }
  return detail::plan_resonances(
      m, breakpoints_x.front(), x_hi, layout, allowed, breakpoints_x,
      [&](double x0) { return nearby(first, d, k, x0); },
      s.max_evaluations / (2 * (detail::kPoleRulePoints + static_cast<std::size_t>(s.kronrod_points))),
      s.cancel);
}

// Where the large-x expansion of Q_ext replaces Mie (rain at optical
// wavelengths), sigma_ext alone is computed and its error is at least the
// expansion's bound; resolving resonances far below that would buy nothing.
// The tolerances are then raised to half that bound (relative), as the first
// panels estimate it: the result's error stays within ~1.5 times the bound.
QuadratureSettings settings_beside_expansion(const std::vector<Panel>& first, const QuadratureSettings& s) {
  double bound = 0, ext = 0;
  for (const auto& p : first) {
    bound += p.kronrod[kAsym];
    ext += p.kronrod[kExt];
  }
  QuadratureSettings t = s;
  if (!(bound > 0) || !(ext > 0)) return t;
  const double floor = std::min(0.5 * bound / ext, 1e-2);
  t.rel_tolerance = std::max(s.rel_tolerance, floor);
  t.angular_tolerance = std::max(detail::angular_tolerance(s), floor);
  return t;
}

BulkOptics integrate_bulk_optics_impl(const SizeDistribution& d, double wavelength, const EfficiencyBatch& q,
                                      const QuadratureSettings& s, std::complex<double> m) {
  if (!(wavelength > 0)) throw std::invalid_argument("wavelength must be > 0");
  if (!(s.rel_tolerance > 0 && s.rel_tolerance < 1)) throw std::invalid_argument("rel_tolerance must lie in (0, 1)");
  const double tail_fraction = s.tail_fraction > 0 ? s.tail_fraction : 1e-3 * s.rel_tolerance;
  const Support support = cross_section_support(d, tail_fraction);
  const Integrator integ(d, wavelength, q, s, m);
  const double k = 2 * kPi / wavelength;
  const std::vector<double> cuts = initial_cuts(support, s, k);
  // A table of many rows has a panel per row at least: refuse before the work.
  // Only the table's own pieces count; a smooth density's steps in ln r can
  // still be merged by the refinement, whose failure names the integral.
  const std::size_t table_pieces = support.breakpoints_m.size() - 1;
  const double floor_evaluations = static_cast<double>(table_pieces) * s.kronrod_points;
  if (table_pieces > 1 && floor_evaluations > static_cast<double>(s.max_evaluations))
    throw std::runtime_error("integral over " + d.describe() + ": its " + std::to_string(table_pieces) +
                             " pieces need at least " + significant(floor_evaluations, 3) +
                             " efficiency evaluations, beyond the budget of " + std::to_string(s.max_evaluations) +
                             "; merge rows or bins of the table");
  std::vector<Panel> panels = evaluate_tasks(integ, plain_tasks(cuts));
  const QuadratureSettings t = settings_beside_expansion(panels, s);
  bool extinction_only = false;
  for (const auto& p : panels) extinction_only = extinction_only || p.used_asymptotic;
  const detail::ResonancePlan plan = resonance_plan(integ, panels, support, d, t, m, extinction_only);
  std::size_t probe = 0;
  if (!plan.resolved.empty()) {
    for (const auto& p : panels) probe += p.evaluations;
    panels = evaluate_tasks(integ, tasks_with_resonances(cuts, plan, k));
  }
  Refinement r(integ, std::move(panels), t, plan.unresolved_bound, extinction_only);
  r.refine();
  r.totals();
  std::string missed = r.require_met(d, t.estimate_resonances);
  if (!missed.empty() && !plan.short_of.empty()) missed += "; " + plan.short_of;
  BulkOptics out = bulk_optics_result(r, support, t, tail_fraction, plan);
  out.evaluations += probe;
  // A tolerance raised beside the expansion is one the caller did not get.
  if (t.rel_tolerance > s.rel_tolerance) {
    const std::string expansion = "sigma_ext: relative tolerance " + significant(s.rel_tolerance, 3) +
                                  " not reachable: beyond x = " + significant(s.asymptotic_x, 6) +
                                  " Q_ext's large-x expansion replaces Mie, and its error bound (calibrated, "
                                  "resonance.hpp) is " +
                                  significant(out.extinction.asymptotic_error / out.extinction.value, 3) +
                                  " of sigma_ext";
    missed = missed.empty() ? expansion : expansion + "; " + missed;
  }
  if (!missed.empty()) {
    out.shortfall = missed;
    out.method += "; tolerance not met: " + out.shortfall;
  }
  return out;
}

}  // namespace

double detail::angular_tolerance(const QuadratureSettings& s) {
  return s.angular_tolerance > 0 ? s.angular_tolerance : std::max(s.rel_tolerance, 1e-6);
}

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
