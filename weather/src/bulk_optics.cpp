// Adaptive Gauss-Kronrod integration of efficiencies over a size distribution.
#include "attenuvis/weather/bulk_optics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "attenuvis/weather/resonance.hpp"

namespace attenuvis::weather {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Components integrated together: ext, sca, abs, g*sca, asymptotic-bound, and
// the weight pi r^2 n(r) alone (the geometric cross-section of the panel).
constexpr int kExt = 0, kSca = 1, kAbs = 2, kGSca = 3, kAsym = 4, kWeight = 5, kComponents = 6;
using Vec = std::array<double, kComponents>;

struct Panel {
  double a = 0, b = 0;  // in u = ln r
  Vec kronrod{}, error{};
  double qext_max = 0;
  double x_span = 0;  // size-parameter width of the panel
  bool floor = false; // narrower than the resonance floor: not split, its error counted as resonance error
};

// Rule nodes/weights on [-1, 1] taken from Boost.Math's gauss_kronrod tables.
struct Rule {
  std::vector<double> abscissa, kronrod_weight, gauss_weight;
  int points = 0;
};

template <unsigned N>
Rule make_rule() {
  using GK = boost::math::quadrature::gauss_kronrod<double, N>;
  using G = boost::math::quadrature::gauss<double, (N - 1) / 2>;
  Rule r;
  const auto& x = GK::abscissa();
  const auto& w = GK::weights();
  r.abscissa.assign(x.begin(), x.end());
  r.kronrod_weight.assign(w.begin(), w.end());
  // Boost stores the Kronrod abscissae with the embedded Gauss nodes at even
  // indices when the Gauss order is odd (0 is then a Gauss node) and at odd
  // indices otherwise; the Gauss weight of node i is G::weights()[i / 2]
  // (same layout as gauss_kronrod::integrate_non_adaptive_m1_1).
  r.gauss_weight.assign(x.size(), 0.0);
  unsigned first = (((N - 1) / 2) & 1) ? 0 : 1;
  for (unsigned i = first; i < x.size(); i += 2) r.gauss_weight[i] = G::weights()[i / 2];
  r.points = static_cast<int>(N);
  return r;
}

Rule rule_for(int points) {
  switch (points) {
    case 15: return make_rule<15>();
    case 21: return make_rule<21>();
    case 31: return make_rule<31>();
    case 41: return make_rule<41>();
    case 51: return make_rule<51>();
    case 61: return make_rule<61>();
    default:
      throw std::invalid_argument("Gauss-Kronrod order " + std::to_string(points) +
                                  " is not available (15, 21, 31, 41, 51 or 61)");
  }
}

class Integrator {
 public:
  Integrator(const SizeDistribution& d, double wavelength, const EfficiencyFunction& q, const QuadratureSettings& s)
      : d_(d), k_(2 * kPi / wavelength), q_(q), s_(s), rule_(rule_for(s.kronrod_points)),
        resolved_x_span_(0.6 * s.kronrod_points) {}

  // Integrand in u = ln r:  r n(r) pi r^2 {Q_ext, Q_sca, Q_abs, g Q_sca, bound}.
  Vec integrand(double u, double& qext) {
    ++evaluations_;
    double r = std::exp(u), x = k_ * r;
    double w = r * d_.density(r) * kPi * r * r;
    Vec f{};
    max_x_ = std::max(max_x_, x);
    if (s_.asymptotic_x > 0 && x > s_.asymptotic_x) {
      used_asymptotic_ = true;
      qext = qext_asymptotic(x);
      f[kExt] = w * qext;
      f[kAsym] = w * qext_asymptotic_bound(x, m_for_bound);
      f[kWeight] = w;
      return f;
    }
    Efficiency e = q_(x);
    qext = e.qext;
    f[kExt] = w * e.qext;
    f[kSca] = w * e.qsca;
    f[kAbs] = w * e.qabs;
    f[kGSca] = w * e.g * e.qsca;
    f[kWeight] = w;
    return f;
  }

  Panel evaluate(double a, double b) {
    Panel p;
    p.a = a;
    p.b = b;
    double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    Vec k{}, g{}, q_min, q_max;
    q_min.fill(INFINITY);
    q_max.fill(-INFINITY);
    for (std::size_t i = 0; i < rule_.abscissa.size(); ++i) {
      double xi = rule_.abscissa[i];
      int copies = (i == 0) ? 1 : 2;
      for (int sgn = 0; sgn < copies; ++sgn) {
        double qext = 0;
        Vec f = integrand(mid + (sgn ? -xi : xi) * half, qext);
        p.qext_max = std::max(p.qext_max, std::abs(qext));
        for (int c = 0; c < kComponents; ++c) {
          k[c] += rule_.kronrod_weight[i] * f[c];
          g[c] += rule_.gauss_weight[i] * f[c];
          if (f[kWeight] > 0) {
            double q = f[c] / f[kWeight];
            q_min[c] = std::min(q_min[c], q);
            q_max[c] = std::max(q_max[c], q);
          }
        }
      }
    }
    for (int c = 0; c < kComponents; ++c) {
      p.kronrod[c] = half * k[c];
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
      for (int c : {kExt, kSca, kAbs, kGSca}) {
        double range = std::isfinite(q_max[c] - q_min[c]) ? q_max[c] - q_min[c] : 0.0;
        p.error[c] += 1.5 * range * std::abs(p.kronrod[kWeight]);
      }
    return p;
  }

  std::complex<double> m_for_bound{1.33, 0};
  std::size_t evaluations_ = 0;
  double max_x_ = 0;
  bool used_asymptotic_ = false;

 private:
  const SizeDistribution& d_;
  double k_;
  const EfficiencyFunction& q_;
  QuadratureSettings s_;
  Rule rule_;
  double resolved_x_span_;  // x-width a panel may span and still trust |K - G|
};

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

}  // namespace

BulkOptics integrate_bulk_optics_impl(const SizeDistribution& d, double wavelength, const EfficiencyFunction& q,
                                      const QuadratureSettings& s, std::complex<double> m) {
  if (!(wavelength > 0)) throw std::invalid_argument("wavelength must be > 0");
  if (!(s.rel_tolerance > 0 && s.rel_tolerance < 1)) throw std::invalid_argument("rel_tolerance must lie in (0, 1)");
  double tail_fraction = s.tail_fraction > 0 ? s.tail_fraction : 1e-3 * s.rel_tolerance;
  Support support;
  try {
    support = d.support(2.0, tail_fraction);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("sigma_ext integral diverges: ") + e.what());
  }
  if (!(support.total_moment > 0) || !std::isfinite(support.total_moment))
    throw std::runtime_error("sigma_ext integral diverges or is empty: the geometric cross-section moment "
                             "int r^2 n(r) dr is " + fmt(support.total_moment));

  Integrator integ(d, wavelength, q, s);
  integ.m_for_bound = m;
  double k = 2 * kPi / wavelength;

  // Initial panels: the support's smooth pieces in ln r, each cut into steps
  // of at most 0.25 in ln r and at the asymptotic switch, so the first pass
  // already sees the shape of the weight.
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

  std::vector<Panel> panels;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i] >= u_lo && cuts[i + 1] <= u_hi) panels.push_back(integ.evaluate(cuts[i], cuts[i + 1]));

  Vec floor_error{};
  auto totals = [&](Vec& value, Vec& error) {
    value.fill(0);
    error.fill(0);
    floor_error.fill(0);
    for (const auto& p : panels)
      for (int c = 0; c < kComponents; ++c) {
        value[c] += p.kronrod[c];
        (p.floor ? floor_error : error)[c] += p.error[c];
      }
  };
  // Nearly non-absorbing spheres: panels are not split below resonance_x_span
  // in x; what such panels still disagree on (|K - G| and the aliasing bound)
  // is resonance structure finer than the floor, reported as resonance error.
  double x_floor = s.estimate_resonances ? s.resonance_x_span : 0.0;
  Vec value{}, error{};
  totals(value, error);
  // Each component's error is measured against the scale it is reported on:
  // sigma_ext for ext/sca/abs, sigma_sca for g*sigma_sca (the asymmetry).
  auto scale = [&](int c, const Vec& v) {
    double ext = std::abs(v[kExt]);
    if (c == kGSca) return std::max(std::abs(v[kSca]), 1e-300);
    return std::max(ext, 1e-300);
  };
  auto converged = [&](const Vec& v, const Vec& e) {
    for (int c : {kExt, kSca, kAbs, kGSca})
      if (e[c] > s.rel_tolerance * scale(c, v)) return false;
    return true;
  };
  Vec scale0{};
  for (int c = 0; c < kComponents; ++c) scale0[c] = scale(c, value);
  auto key = [&](const Panel& p) {
    double worst = 0;
    for (int c : {kExt, kSca, kAbs, kGSca}) worst = std::max(worst, p.error[c] / scale0[c]);
    return worst;
  };
  auto cmp = [&](std::size_t i, std::size_t j) { return key(panels[i]) < key(panels[j]); };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(cmp)> heap(cmp);
  for (std::size_t i = 0; i < panels.size(); ++i) heap.push(i);

  std::size_t iterations = 0;
  while (!converged(value, error) && !heap.empty()) {
    if (integ.evaluations_ > s.max_evaluations) break;
    std::size_t i = heap.top();
    heap.pop();
    Panel p = panels[i];
    double mid = 0.5 * (p.a + p.b);
    if (!(mid > p.a && mid < p.b) || (p.b - p.a) < 1e-12) continue;  // cannot split further
    if (0.5 * p.x_span < x_floor) {
      panels[i].floor = true;
      for (int c = 0; c < kComponents; ++c) error[c] -= p.error[c];
      continue;
    }
    Panel left = integ.evaluate(p.a, mid), right = integ.evaluate(mid, p.b);
    for (int c = 0; c < kComponents; ++c) {
      value[c] += left.kronrod[c] + right.kronrod[c] - p.kronrod[c];
      error[c] += left.error[c] + right.error[c] - p.error[c];
    }
    panels[i] = left;
    panels.push_back(right);
    heap.push(i);
    heap.push(panels.size() - 1);
    if (++iterations % 256 == 0) totals(value, error);  // keep the running sums from drifting
  }
  totals(value, error);

  if (!converged(value, error)) {
    const char* names[] = {"sigma_ext", "sigma_sca", "sigma_abs", "asymmetry g"};
    int worst = kExt;
    double ratio = 0;
    for (int c : {kExt, kSca, kAbs, kGSca})
      if (error[c] / scale(c, value) > ratio) { ratio = error[c] / scale(c, value); worst = c; }
    throw std::runtime_error(std::string(names[worst]) + " integral over " + d.describe() + ": relative tolerance " +
                             fmt(s.rel_tolerance) + " not met after " + std::to_string(integ.evaluations_) +
                             " efficiency evaluations (estimated quadrature error " + fmt(ratio) +
                             " relative); the integrand is too rough or too wide for the evaluation budget "
                             "(raise max_evaluations or the tolerance)");
  }

  BulkOptics out;
  out.evaluations = integ.evaluations_;
  out.max_size_parameter = integ.max_x_;
  out.scattering_computed = !integ.used_asymptotic_;
  double qext_max = 0;
  for (const auto& p : panels) qext_max = std::max(qext_max, p.qext_max);
  // Tail bound: |Q| <= max(4, 2 max sampled Q_ext) over the omitted radii.
  // Q_ext of a sphere stays below 4 for the refractive indices of water and ice
  // (its first maximum, near x (n-1) = 2, is ~3.2 for n = 1.33); the factor 2
  // covers what the samples missed.  The tails hold tail_fraction of the r^2
  // moment, 1e-3 of the tolerance by default, so this bound is never limiting.
  double q_bound = std::max(4.0, 2 * qext_max);
  double tail = q_bound * kPi * support.omitted_moment;

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
    out.extinction.resonance_error = floor_error[kExt];
    out.scattering.resonance_error = floor_error[kSca];
    out.absorption.resonance_error = floor_error[kAbs];
    out.floor_panels = 0;
    for (const auto& p : panels) out.floor_panels += p.floor ? 1 : 0;
  }
  if (out.scattering_computed && value[kExt] > 0) {
    out.albedo = value[kSca] / value[kExt];
    out.albedo_error = (out.scattering.error() + out.albedo * out.extinction.error()) / value[kExt];
    out.asymmetry = value[kSca] > 0 ? value[kGSca] / value[kSca] : 0;
    out.asymmetry_error = value[kSca] > 0 ? (error[kGSca] + tail + std::abs(out.asymmetry) * out.scattering.error()) /
                                                value[kSca]
                                          : 0;
  }
  std::ostringstream method;
  method << "adaptive Gauss-Kronrod " << s.kronrod_points << " (Boost.Math) in ln r, rel. tol " << s.rel_tolerance
         << ", tails cut at " << tail_fraction << " of the r^2 moment, " << out.evaluations << " evaluations, x <= "
         << fmt(out.max_size_parameter);
  if (integ.used_asymptotic_) method << ", Q_ext large-x expansion beyond x = " << s.asymptotic_x;
  out.method = method.str();
  return out;
}

BulkOptics integrate_bulk_optics(const SizeDistribution& d, double wavelength_m, const EfficiencyFunction& q,
                                 const QuadratureSettings& s, std::complex<double> m) {
  QuadratureSettings t = s;
  if (m.imag() >= resonance_free_k()) t.estimate_resonances = false;
  return integrate_bulk_optics_impl(d, wavelength_m, q, t, m);
}

}  // namespace attenuvis::weather
