// sigma_ext of a table or a power law by Cauchy's theorem on each of its
// pieces: see segmented_contour.hpp.
#include "attenuvis/weather/segmented_contour.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include <tbb/parallel_for.h>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "attenuvis/weather/detail/analytic_density.hpp"
#include "contour_panel.hpp"
#include "gauss_kronrod_rule.hpp"

namespace attenuvis::weather {
using io::significant;
namespace {

constexpr double kPi = boost::math::constants::pi<double>();
using Complex = std::complex<double>;

// The density between two breakpoints, continued to complex r: a straight
// line n0 + slope (r - r0) (a table's segment, or zero in a gap between bins),
// c r^-nu (a power law, principal branch), or a log-normal cut at r0 and r1
// (N / (sqrt(2 pi) s r) exp(-z^2 / 2), z = (ln r - ln r_g) / s, principal
// branch: analytic in the upper half-plane).
struct Piece {
  double r0 = 0, r1 = 0;
  double n0 = 0, slope = 0, n1 = 0;  // straight line, and its end value as tabulated
  bool power = false;
  double c = 0, nu = 0;              // power law
  std::optional<LogNormal> log_normal;
  bool curved() const { return power || log_normal.has_value(); }
  bool zero() const { return !curved() && n0 == 0 && slope == 0; }
  Complex at(Complex r) const {
    if (log_normal) return detail::log_normal_density(*log_normal, r);
    return power ? c * std::exp(-nu * std::log(r)) : n0 + slope * (r - r0);
  }
  double value_at(double r) const {
    if (log_normal) return detail::log_normal_density(*log_normal, r);
    return power ? c * std::pow(r, -nu) : n0 + slope * (r - r0);
  }
  double slope_at(double r) const {
    if (log_normal) {  // dn/dr = -n (1 + z / s) / r
      const double s = std::log(log_normal->sigma_g), z = (std::log(r) - std::log(log_normal->median_radius_m)) / s;
      return -value_at(r) * (1 + z / s) / r;
    }
    return power ? -nu * c * std::pow(r, -nu - 1) : slope;
  }
};

// The jump and the change of slope (both in SI, the slope per metre) of the
// density at breakpoint k of `pieces` (k = pieces.size(): the far end), at
// radius r, right minus left.  Between two straight pieces of a table the
// jump is exact (n1 of the left segment against n0 of the right one) rather
// than a difference of two rounded evaluations.
struct Difference {
  double jump = 0, slope_change = 0;
};
Difference difference_at(const std::vector<Piece>& pieces, std::size_t k, double r) {
  const Piece* right = k < pieces.size() ? &pieces[k] : nullptr;
  const Piece* left = k > 0 ? &pieces[k - 1] : nullptr;
  const double left_value = left ? (left->curved() ? left->value_at(r) : left->n1) : 0.0;
  const double right_value = right ? right->value_at(r) : 0.0;
  return {right_value - left_value, (right ? right->slope_at(r) : 0.0) - (left ? left->slope_at(r) : 0.0)};
}

// A table's segment from (r0, n0) to (r1, n1).
Piece straight(double r0, double r1, double n0, double n1) {
  Piece p;
  p.r0 = r0, p.r1 = r1, p.n0 = n0, p.n1 = n1;
  p.slope = (n1 - n0) / (r1 - r0);
  return p;
}

// The pieces in increasing r, gaps filled with zero pieces; nothing for the
// distributions that have an analytic continuation of their own, and for a
// truncated log-normal unless `truncated_log_normal`.
std::optional<std::vector<Piece>> pieces_of(const SizeDistribution& d, bool truncated_log_normal) {
  std::vector<Piece> out;
  if (const auto* l = std::get_if<LogNormal>(&d.form())) {
    if (!truncated_log_normal || !(l->r_min_m > 0) || !std::isfinite(l->r_max_m)) return std::nullopt;
    Piece piece;
    piece.r0 = l->r_min_m;
    piece.r1 = l->r_max_m;
    piece.log_normal = *l;
    out.push_back(piece);
    return out;
  }
  if (const auto* p = std::get_if<PowerLaw>(&d.form())) {
    Piece piece;
    piece.r0 = p->r_min_m;
    piece.r1 = p->r_max_m;
    piece.power = true;
    piece.c = p->c;
    piece.nu = p->nu;
    out.push_back(piece);
    return out;
  }
  const auto* t = std::get_if<Tabulated>(&d.form());
  if (!t) return std::nullopt;
  for (const auto& s : t->segments) {
    if (!(s.r1 > s.r0)) continue;  // a zero-width segment holds no particles
    if (!out.empty() && s.r0 < out.back().r1)
      throw std::invalid_argument("tabulated distribution " + d.describe() + ": segments overlap or are not in order");
    if (!out.empty() && s.r0 > out.back().r1) out.push_back(straight(out.back().r1, s.r0, 0, 0));
    out.push_back(straight(s.r0, s.r1, s.n0, s.n1));
  }
  if (out.empty()) return std::nullopt;
  return out;
}

// Where a panel lies: on the path over piece `index`, on the path over a run
// of short straight pieces (a table's rows, by product integration), or on
// the leg up from breakpoint `index`.
enum class Where { path, span, leg };

struct Panel {
  Where where = Where::path;
  std::size_t index = 0;
  detail::PathPanel quad;
  double near_axis = 0;  // bound on what the rule cannot see below its lowest node (legs touching the axis)
  double charged() const { return quad.error + near_axis; }
};

// Pieces whose path spans at least this many panels take a Gauss-Kronrod
// rule of at least this order (Integrand::path_rule).  Measured at 1e-9 on
// raindrop bins (0.5-1 mm, water): 14,115 -> 4,743 evaluations at 550 nm and
// 39,525 -> 12,431 at 200 nm against the 15-point rule; orders 41-61 on
// wider panels gain no more.
constexpr double kLongPiecePanels = 4;
constexpr int kLongPieceKronrodPoints = 31;
// The ripple that height H leaves of S(0) on such a piece has the period
// pi / (Re m - 1) in x (the interference of the central ray with the
// diffracted wave, 2 x (m - 1) in phase, van de Hulst 1957 Sec. 11.22); the
// 31-point rule's Gauss part resolves ~5 of its periods per panel and fails
// abruptly beyond (water at 1e-9: 5.3 periods pass at 550 nm, 6.3 fail at
// 200 nm), so the first panels span 5, and no fewer than 40 units of x,
// nor more than twice that (absorbing drops, whose ripple is damped).
// Measured at 1e-9 on the 0.5-1 mm bin: 4,613 -> 3,962 evaluations at 550 nm,
// 1,761 -> 1,482 at 1.55 um, 428 -> 304 at 10.6 um, 12,333 at 200 nm (40 wide).
constexpr double kLongPieceRipplePeriods = 5;
constexpr double kLongPieceMaxWidths = 2;
// Runs of a table's short rows are integrated in spans by product
// integration with the same 31-point rule (product_rule.hpp), whose
// interpolant is exact to degree 30 rather than the rule's 46: panels start
// at this fraction of panel_width.
constexpr double kSpanPanelWidths = 0.5;

// |S(0)| on the real axis: <= 1/2 sum (2n+1)(|a_n| + |b_n|) <= (N + 1)^2, the
// series cut where Wiscombe's (1980) criterion ends it.
double forward_amplitude_bound(double x) {
  const double terms = x + 4.05 * std::cbrt(x) + 2;
  return (terms + 1) * (terms + 1);
}

class Integrand {
 public:
  Integrand(std::vector<Piece> pieces, double wavelength, Complex m, const SegmentedContourSettings& s,
            mie::Precision arithmetic)
      : pieces_(std::move(pieces)),
        k_(2 * kPi / wavelength),
        scale_(4 * kPi / (k_ * k_ * k_)),
        m_(m),
        s_(s),
        rule_(detail::rule_for(s.kronrod_points)),
        long_rule_(detail::rule_for(std::max(s.kronrod_points, kLongPieceKronrodPoints))),
        span_rule_(long_rule_),
        arithmetic_(arithmetic) {
    for (const Piece& p : pieces_) breakpoint_x_.push_back(k_ * p.r0);
    breakpoint_x_.push_back(k_ * pieces_.back().r1);
  }

  std::size_t breakpoints() const { return pieces_.size() + 1; }
  double x_at(std::size_t k) const { return k_ * (k < pieces_.size() ? pieces_[k].r0 : pieces_.back().r1); }
  bool zero_piece(std::size_t i) const { return pieces_[i].zero(); }
  double height(double t) const { return s_.height * std::tanh(s_.angle * t / s_.height); }

  // The jump and the change of slope (both in SI, the slope per metre) of
  // the density at breakpoint k, right minus left.
  void difference_at(std::size_t k, double& jump, double& slope_change) const {
    ATTENUVIS_CHECK_LT(k, breakpoints());
    const Difference d = weather::difference_at(pieces_, k, x_at(k) / k_);
    jump = d.jump, slope_change = d.slope_change;
  }
  bool curved_at(std::size_t k) const {
    return (k < pieces_.size() && pieces_[k].curved()) || (k > 0 && pieces_[k - 1].curved());
  }
  bool leg_vanishes(std::size_t k) const {
    double jump = 0, slope_change = 0;
    difference_at(k, jump, slope_change);
    return !curved_at(k) && jump == 0 && slope_change == 0;
  }

  // The path over a piece many panels long (a raindrop bin spans thousands
  // of units of x) runs along the ripple that height H leaves of S(0), many
  // periods per panel: a rule of higher order integrates it with fewer
  // evaluations (and its |K - G| is nearer its error), while the narrow
  // pieces of a table keep the settings' rule (one panel each: fewer nodes).
  const detail::Rule& path_rule(std::size_t i) const {
    return long_piece(i) ? long_rule_ : rule_;
  }
  bool long_piece(std::size_t i) const {
    return k_ * (pieces_[i].r1 - pieces_[i].r0) >= kLongPiecePanels * s_.panel_width;
  }
  // Pieces whose path is taken in spans (span_panel): a table's short rows.
  bool spanned_piece(std::size_t i) const { return !pieces_[i].curved() && !long_piece(i); }
  // The width of the first panels over piece i: on a long piece, as many
  // periods of the ripple as its rule resolves (kLongPieceRipplePeriods),
  // between panel_width and kLongPieceMaxWidths times that.
  double panel_width(std::size_t i) const {
    if (!long_piece(i) || !(m_.real() > 1)) return s_.panel_width;
    const double period = kPi / (m_.real() - 1);
    return std::clamp(kLongPieceRipplePeriods * period, s_.panel_width, kLongPieceMaxWidths * s_.panel_width);
  }

  Panel path_panel(std::size_t i, double a, double b) const {
    const Piece& piece = pieces_[i];
    const double H = s_.height, theta = s_.angle;
    Panel p;
    p.where = Where::path;
    p.index = i;
    p.quad = detail::evaluate_path_panel(
        path_rule(i), a, b, [&](double t) { return Complex(t, height(t)); },
        [&](double t) {
          const double c = 1 / std::cosh(theta * t / H);
          return Complex(1.0, theta * c * c);
        },
        [&](Complex x) { return scale_ * piece.at(x / k_); }, m_, arithmetic_);
    return p;
  }

  // The path over [a, b] in t across the spanned pieces there: their
  // straight densities continued to the path do not join (they differ by
  // slope change x i h at each breakpoint), so the panel integrates each
  // piece's line against the interpolant of S(0) (product_rule.hpp).
  Panel span_panel(double a, double b) const {
    const double H = s_.height, theta = s_.angle, centre = 0.5 * (a + b);
    std::vector<detail::ProductRule::Segment> segments;
    std::size_t i = static_cast<std::size_t>(
        std::upper_bound(breakpoint_x_.begin(), breakpoint_x_.end(), a) - breakpoint_x_.begin());
    for (i = i > 0 ? i - 1 : 0; i < pieces_.size() && breakpoint_x_[i] < b; ++i) {
      const Piece& piece = pieces_[i];
      ATTENUVIS_CHECK(!piece.curved());
      // scale n(x / k) = scale (n0 + slope (x / k - r0)), about x = centre.
      const double alpha = scale_ * (piece.n0 + piece.slope * (centre / k_ - piece.r0));
      segments.push_back({std::max(a, breakpoint_x_[i]), std::min(b, breakpoint_x_[i + 1]), alpha,
                          scale_ * piece.slope / k_});
    }
    Panel p;
    p.where = Where::span;
    p.quad = detail::evaluate_product_panel(
        span_rule_, a, b, segments, [&](double t) { return Complex(t, height(t)); },
        [&](double t) {
          const double c = 1 / std::cosh(theta * t / H);
          return Complex(1.0, theta * c * c);
        },
        m_, arithmetic_);
    return p;
  }

  // The leg up from breakpoint k over y in [a, b]: i int D_k(x_k + i y) dy.
  Panel leg_panel(std::size_t k, double a, double b) const {
    const double xk = x_at(k), rk = xk / k_;
    const Piece* right = k < pieces_.size() ? &pieces_[k] : nullptr;
    const Piece* left = k > 0 ? &pieces_[k - 1] : nullptr;
    double jump = 0, slope_change = 0;
    difference_at(k, jump, slope_change);
    const bool straight = !(right && right->curved()) && !(left && left->curved());
    // Straight pieces: the difference written as jump + slope change x (r - r_k),
    // which is exactly 0 on the axis of a continuous table.
    const auto difference = [&](Complex r) -> Complex {
      if (straight) return jump + slope_change * (r - rk);
      return (right ? right->at(r) : Complex{}) - (left ? left->at(r) : Complex{});
    };
    Panel p;
    p.where = Where::leg;
    p.index = k;
    p.quad = detail::evaluate_path_panel(
        rule_, a, b, [&](double y) { return Complex(xk, y); }, [](double) { return Complex(0, 1); },
        [&](Complex x) { return scale_ * difference(x / k_); }, m_, arithmetic_);
    if (a == 0) p.near_axis = near_axis_bound(k, lowest_node(b));
    return p;
  }

  // Below the lowest node y_1 of a leg's panel on the axis the rule sees
  // nothing of a resonance lying closer to the axis; that part is bounded
  // (segmented_contour.hpp).  A power law's or a log-normal's slope varies
  // along the leg: twice the slope at r_k covers it for y_1 << x_k (for the
  // log-normal, y_1 << x_k / (1 + |z_k| / s): n'' / n' ~ (1 + |z| / s) / r).
  double lowest_node(double height) const { return 0.5 * height * (1 - rule_.abscissa.back()); }
  double near_axis_bound(std::size_t k, double y1) const {
    double jump = 0, slope_change = 0;
    difference_at(k, jump, slope_change);
    const double s_max = forward_amplitude_bound(x_at(k)) * std::exp(2 * y1);
    const double slope = (curved_at(k) ? 2.0 : 1.0) * std::abs(slope_change);
    return 2 * scale_ * s_max * (std::abs(jump) * y1 + slope * y1 * y1 / (2 * k_));
  }
  // Where to cut a leg's panel [0, b] on the axis so that the lower part's
  // bound is about `allowed`: between b/4096 and `largest` (the upper part is
  // split again at its middle if its |K - G| asks).
  double axis_cut(std::size_t k, double b, double allowed, double largest) const {
    double lo = b / 4096, hi = largest;
    if (near_axis_bound(k, lowest_node(hi)) <= allowed) return hi;
    for (int i = 0; i < 40; ++i) {  // bisection in log: the bound grows with the height
      const double mid = std::sqrt(lo * hi);
      (near_axis_bound(k, lowest_node(mid)) <= allowed ? lo : hi) = mid;
    }
    return lo;
  }

  Panel evaluate(Where where, std::size_t index, double a, double b) const {
    throw_if_cancelled(s_.cancel);  // once per panel: kronrod_points Mie evaluations
    switch (where) {
      case Where::path: return path_panel(index, a, b);
      case Where::span: return span_panel(a, b);
      case Where::leg: break;
    }
    return leg_panel(index, a, b);
  }

 private:
  std::vector<Piece> pieces_;
  double k_, scale_;
  Complex m_;
  const SegmentedContourSettings& s_;
  detail::Rule rule_, long_rule_;
  detail::ProductRule span_rule_;
  std::vector<double> breakpoint_x_;  // x at breakpoint k (x_at)
  mie::Precision arithmetic_;
};

// Where a panel is split: at the middle, or, for a leg's panel on the axis,
// low enough that the new near-axis bound is about `allowed` (it falls like
// y_1 or y_1^2).
double split_point(const Integrand& f, const Panel& p, double allowed) {
  if (p.where == Where::leg && p.quad.a == 0) return f.axis_cut(p.index, p.quad.b, allowed, p.quad.b / 8);
  return 0.5 * (p.quad.a + p.quad.b);
}

// A panel to evaluate: where it lies and its interval.
struct Task {
  Where where;
  std::size_t index;
  double a, b;
};

// The path over each piece: edges at the breakpoints, and inside a piece
// every panel_width, graded towards x = 0 up to the rise length 2H/theta as
// contour_extinction.cpp does (resonance poles sit at ~theta x from the low
// path there).
// Runs of two or more spanned pieces are one stretch of path, panels
// spanning their breakpoints.
std::vector<Task> path_tasks(const Integrand& f, const SegmentedContourSettings& s) {
  std::vector<Task> tasks;
  std::vector<double> grid;
  for (double g = s.height / s.angle / 4; g < 2 * s.height / s.angle; g *= 2) grid.push_back(g);
  const auto add = [&](Where where, std::size_t i, double a, double b, double width) {
    std::vector<double> edges{a};
    for (double g : grid)
      if (g > a && g < b) edges.push_back(g);
    const double from = edges.back();
    const int n = std::max(1, static_cast<int>(std::ceil((b - from) / width)));
    for (int j = 1; j <= n; ++j) edges.push_back(j == n ? b : from + (b - from) * j / n);
    for (std::size_t j = 0; j + 1 < edges.size(); ++j) tasks.push_back({where, i, edges[j], edges[j + 1]});
  };
  const std::size_t pieces = f.breakpoints() - 1;
  for (std::size_t i = 0; i < pieces; ++i) {
    std::size_t end = i;
    while (end < pieces && f.spanned_piece(end)) ++end;
    if (s.spans && end >= i + 2) {
      add(Where::span, i, f.x_at(i), f.x_at(end), kSpanPanelWidths * s.panel_width);
      i = end - 1;
    } else if (!f.zero_piece(i)) {
      add(Where::path, i, f.x_at(i), f.x_at(i + 1), f.panel_width(i));
    }
  }
  return tasks;
}

// The breakpoints whose leg does not vanish.
std::size_t leg_count(const Integrand& f) {
  std::size_t legs = 0;
  for (std::size_t kb = 0; kb < f.breakpoints(); ++kb) legs += !f.leg_vanishes(kb);
  return legs;
}

// The legs add ~h^2 / w^2 of sigma_ext (w the width of the distribution in
// x), so the path alone sizes their near-axis budget: each leg starts as
// panels [0, c], [c, 16c], [16c, 256c], ..., h, c set so that the bound below
// its lowest node is a quarter of the leg's share of the tolerance.
std::vector<Task> leg_tasks(const Integrand& f, const std::vector<Panel>& path, const SegmentedContourSettings& s) {
  Complex path_total{};
  for (const auto& p : path) path_total += p.quad.kronrod;
  const double leg_allowed =
      0.25 * s.rel_tolerance * std::abs(path_total.real()) / std::max<std::size_t>(leg_count(f), 1);
  std::vector<Task> tasks;
  for (std::size_t kb = 0; kb < f.breakpoints(); ++kb) {
    if (f.leg_vanishes(kb)) continue;
    const double h = f.height(f.x_at(kb));
    double c = f.axis_cut(kb, h, leg_allowed, h);
    tasks.push_back({Where::leg, kb, 0.0, c});
    for (; c < h; c *= 16) tasks.push_back({Where::leg, kb, c, std::min(16 * c, h)});
  }
  return tasks;
}

struct Sums {
  Complex total;
  double error = 0, near_axis = 0, rounding = 0;
};

Sums sums(const std::vector<Panel>& ps) {
  Sums out;
  for (const auto& p : ps) {
    out.total += p.quad.kronrod;
    out.error += p.quad.error;
    out.near_axis += p.near_axis;
    out.rounding += p.quad.rounding;
  }
  return out;
}

// The panels of the path and the legs and their adaptive refinement: split
// panels until |K - G| plus the near-axis bounds meet the tolerance, then
// (with verification) halve them all and charge the change
// (contour_panel.hpp: refined_sums).
class PieceQuadrature {
 public:
  PieceQuadrature(const Integrand& f, const SizeDistribution& d, const SegmentedContourSettings& s)
      : f_(f), d_(d), s_(s) {}

  std::size_t evaluations() const { return evaluations_; }

  std::vector<Panel> evaluate_all(const std::vector<Task>& ts) {
    std::vector<Panel> out(ts.size());
    tbb::parallel_for(std::size_t(0), ts.size(),
                      [&](std::size_t i) { out[i] = f_.evaluate(ts[i].where, ts[i].index, ts[i].a, ts[i].b); });
    for (const auto& p : out) evaluations_ += p.quad.evaluations;
    return out;
  }

  Sums converged_sums(std::vector<Panel>& panels, bool verify) {
    return detail::refined_sums(
        panels, verify, [&](std::vector<Panel>& ps) { refine(ps); }, sums,
        [&](const std::vector<Panel>& ps) { return halves_of(ps, detail::every_index(ps.size()), 0.0); },
        [&](const Sums& fine) {
          require_finite(fine);
          if (fine.error + fine.near_axis <= s_.rel_tolerance * std::abs(fine.total.real())) return true;
          check_budget("verified quadrature error", fine.error + fine.near_axis, fine);
          return false;
        });
  }

 private:
  std::vector<Panel> halves_of(const std::vector<Panel>& ps, const std::vector<std::size_t>& which, double allowed) {
    std::vector<Panel> halves(2 * which.size());
    tbb::parallel_for(std::size_t(0), halves.size(), [&](std::size_t j) {
      const Panel& p = ps[which[j / 2]];
      const double cut = split_point(f_, p, allowed > 0 ? allowed : p.near_axis / 8);
      halves[j] =
          j % 2 == 0 ? f_.evaluate(p.where, p.index, p.quad.a, cut) : f_.evaluate(p.where, p.index, cut, p.quad.b);
    });
    for (const auto& h : halves) evaluations_ += h.quad.evaluations;
    return halves;
  }

  void require_finite(const Sums& sum) const {
    if (!std::isfinite(sum.total.real()) || !std::isfinite(sum.error) || !std::isfinite(sum.near_axis))
      throw std::runtime_error("sigma_ext by segmented contour over " + d_.describe() +
                               ": the integral is not finite in double precision (sum " +
                               significant(sum.total.real(), 3) + "); the distribution's number density is out of range");
  }

  void check_budget(const char* what, double error, const Sums& sum) const {
    detail::check_evaluation_budget("sigma_ext by segmented contour", what, error / std::abs(sum.total.real()),
                                    s_.rel_tolerance, evaluations_, s_.max_evaluations);
  }

  // Adaptive: split panels until |K - G| plus the near-axis bounds meet the target.
  void refine(std::vector<Panel>& ps) {
    for (;;) {
      const Sums sum = sums(ps);
      require_finite(sum);
      const double target = s_.rel_tolerance * std::abs(sum.total.real());
      if (sum.error + sum.near_axis <= target) return;
      check_budget("quadrature error", sum.error + sum.near_axis, sum);
      const double share = target / static_cast<double>(ps.size());
      std::vector<std::size_t> split = largest_charges(ps, sum.error + sum.near_axis - 0.5 * target);
      ps = detail::with_halves(ps, split, halves_of(ps, split, 0.5 * share));
    }
  }

  // The largest charges first, until they cover the excess over half the
  // target (the halves keep some of it); at least the worst, so every round
  // spends evaluations and the budget ends the loop.  Which ones depends on
  // the values alone, not on the thread count.  In increasing index.
  static std::vector<std::size_t> largest_charges(const std::vector<Panel>& ps, double excess) {
    std::vector<std::size_t> order = detail::every_index(ps.size());
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t i, std::size_t j) { return ps[i].charged() > ps[j].charged(); });
    std::vector<std::size_t> split;
    double taken = 0;
    for (std::size_t i : order) {
      if (!split.empty() && taken >= excess) break;
      split.push_back(i);
      taken += ps[i].charged();
    }
    std::sort(split.begin(), split.end());
    return split;
  }

  const Integrand& f_;
  const SizeDistribution& d_;
  const SegmentedContourSettings& s_;
  std::size_t evaluations_ = 0;
};

std::string method_text(const SizeDistribution& d, const SegmentedContourSettings& s, std::size_t pieces,
                        std::size_t legs, bool spans, bool verify, mie::Precision arithmetic,
                        std::size_t evaluations, double x_max) {
  std::ostringstream method;
  method << "segmented contour: Cauchy on each of " << pieces << " pieces of the "
         << (std::holds_alternative<PowerLaw>(d.form())  ? "power law"
             : std::holds_alternative<LogNormal>(d.form()) ? "cut log-normal"
                                                            : "table")
         << ", path x = t + i h(t), h <= " << significant(s.height, 3) << ", with " << legs
         << " legs down to the breakpoints, near-axis parts bounded (segmented_contour.hpp), Gauss-Kronrod "
         << s.kronrod_points << " (Boost.Math; on pieces spanning " << kLongPiecePanels << " panels or more, "
         << std::max(s.kronrod_points, kLongPieceKronrodPoints) << ")"
         << (spans ? ", short rows' path in spans across them by product integration" : "")
         << (verify ? ", verified by halving" : "")
         << ", S(0) in "
         << (arithmetic == mie::Precision::double_precision ? "double" : "long double") << ", rel. tol "
         << significant(s.rel_tolerance, 3) << ", " << evaluations << " evaluations, x <= " << significant(x_max, 3);
  return method.str();
}

// Evaluations per unit of x on a long piece's path, per short piece, per leg
// at a change of slope and at a jump, per unit of x and at least on a span
// of short rows (10,000 log-normal rows at 550 nm: 373,881 evaluations, of
// which the path's spans ~1,400), and the CPU cost of one evaluation
// (validation/bench/forward_amplitude_speed: 0.9 us at x = 100, 46 us at
// 1e4), from the runs quoted in segmented_contour.hpp, rounded up.
constexpr double kEvaluationsPerX = 0.85, kEvaluationsPerLeg = 40, kEvaluationsPerJumpLeg = 120;
constexpr double kEvaluationsPerSpanX = 2, kEvaluationsPerSpan = 31;
constexpr double kSecondsPerTerm = 5e-9, kSecondsPerEvaluation = 0.45e-6;

}  // namespace

ContourCost segmented_contour_cost(const SizeDistribution& d, double wavelength_m, const SegmentedContourSettings& s) {
  ContourCost cost;
  const auto pieces = pieces_of(d, s.truncated_log_normal);
  if (!pieces) return cost;
  const double k = 2 * kPi / wavelength_m;
  auto add = [&](double evaluations, double x) {
    cost.evaluations += evaluations;
    cost.seconds += evaluations * (kSecondsPerEvaluation + kSecondsPerTerm * x);
  };
  // As path_tasks: runs of two or more short straight pieces in spans.
  const auto spanned = [&](std::size_t i) {
    const Piece& p = (*pieces)[i];
    return !p.curved() && k * (p.r1 - p.r0) < kLongPiecePanels * s.panel_width;
  };
  for (std::size_t i = 0; i < pieces->size(); ++i) {
    std::size_t end = i;
    while (end < pieces->size() && spanned(end)) ++end;
    const Piece& p = (*pieces)[i];
    if (s.spans && end >= i + 2) {
      const double xa = k * p.r0, xb = k * (*pieces)[end - 1].r1;
      add(std::max(kEvaluationsPerSpan, (xb - xa) * kEvaluationsPerSpanX), 0.5 * (xa + xb));
      i = end - 1;
    } else if (!p.zero()) {
      const double xa = k * p.r0, xb = k * p.r1;
      add(std::max<double>(s.kronrod_points, (xb - xa) * kEvaluationsPerX), 0.5 * (xa + xb));
    }
  }
  // A leg where the density jumps or changes slope, or a curved piece ends (Integrand::leg_vanishes).
  for (std::size_t i = 0; i <= pieces->size(); ++i) {
    const double r = i < pieces->size() ? (*pieces)[i].r0 : pieces->back().r1;
    const Difference d = difference_at(*pieces, i, r);
    const bool curved = (i < pieces->size() && (*pieces)[i].curved()) || (i > 0 && (*pieces)[i - 1].curved());
    if (d.jump != 0) add(kEvaluationsPerJumpLeg, k * r);
    else if (d.slope_change != 0 || curved) add(kEvaluationsPerLeg, k * r);
  }
  return cost;
}

std::optional<ContourExtinction> segmented_contour_extinction(const SizeDistribution& d, double wavelength_m,
                                                              Complex m, const SegmentedContourSettings& s) {
  auto pieces = pieces_of(d, s.truncated_log_normal);
  if (!pieces) return std::nullopt;
  const double k = 2 * kPi / wavelength_m;
  const double x_min = k * pieces->front().r0, x_max = k * pieces->back().r1;
  if (!(x_max <= s.max_x) || !(x_min > 0)) return std::nullopt;
  const ContourCost cost = segmented_contour_cost(d, wavelength_m, s);
  if (cost.seconds > s.max_seconds)
    throw std::runtime_error("sigma_ext by segmented contour over " + d.describe() + ": " +
                             std::to_string(pieces->size()) + " pieces up to x = " + significant(x_max, 3) +
                             " are estimated to take " + significant(cost.evaluations, 2) + " Mie evaluations (~" +
                             significant(cost.seconds, 2) + " s of one core), beyond the limit of " +
                             significant(s.max_seconds, 3) + " s; merge rows or bins of the table");
  // The budget: the settings', or twice the estimate (a table of many rows).
  SegmentedContourSettings run = s;
  run.max_evaluations = std::max(s.max_evaluations, static_cast<std::size_t>(2 * cost.evaluations));
  const mie::Precision arithmetic = detail::contour_arithmetic(run.rel_tolerance, run.height);
  const Integrand f(std::move(*pieces), wavelength_m, m, run, arithmetic);

  // The path first, then the legs, whose budget the path's sum sets.
  PieceQuadrature quadrature(f, d, run);
  const std::vector<Task> path = path_tasks(f, run);
  const bool spans = std::any_of(path.begin(), path.end(), [](const Task& t) { return t.where == Where::span; });
  std::vector<Panel> panels = quadrature.evaluate_all(path);
  for (Panel& p : quadrature.evaluate_all(leg_tasks(f, panels, run))) panels.push_back(std::move(p));
  // Verification by halving, as contour_extinction.cpp: |K - G| stalls where
  // the ripple left at height H is not far below the tolerance.
  const bool verify = s.verify || detail::ripple_residual(m, s.height * std::tanh(s.angle * x_max / s.height)) >
                                      1e-2 * s.rel_tolerance;
  const Sums fine = quadrature.converged_sums(panels, verify);

  ContourExtinction out;
  out.extinction.value = fine.total.real();
  out.extinction.quadrature_error = fine.error;
  out.extinction.resonance_error = fine.near_axis;
  out.extinction.rounding_error = fine.rounding;
  out.evaluations = quadrature.evaluations();
  out.max_size_parameter = x_max;
  out.height = s.height;
  out.angle = s.angle;
  out.verified = verify;
  out.method =
      method_text(d, s, f.breakpoints() - 1, leg_count(f), spans, verify, arithmetic, out.evaluations, x_max);
  return out;
}

}  // namespace attenuvis::weather
