// The pieces of a table or a power law and the integrand of the segmented
// contour over them (segmented_contour.hpp): the density continued to
// complex r piece by piece, and the panels of the path and of the legs.
// Private to segmented_contour.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <optional>
#include <stdexcept>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include "attenuvis/io/check.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "attenuvis/weather/detail/analytic_density.hpp"
#include "attenuvis/weather/segmented_contour.hpp"
#include "contour_panel.hpp"
#include "gauss_kronrod_rule.hpp"

namespace attenuvis::weather::detail::segmented {
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
inline Difference difference_at(const std::vector<Piece>& pieces, std::size_t k, double r) {
  const Piece* right = k < pieces.size() ? &pieces[k] : nullptr;
  const Piece* left = k > 0 ? &pieces[k - 1] : nullptr;
  const double left_value = left ? (left->curved() ? left->value_at(r) : left->n1) : 0.0;
  const double right_value = right ? right->value_at(r) : 0.0;
  return {right_value - left_value, (right ? right->slope_at(r) : 0.0) - (left ? left->slope_at(r) : 0.0)};
}

// A table's segment from (r0, n0) to (r1, n1).
inline Piece straight(double r0, double r1, double n0, double n1) {
  Piece p;
  p.r0 = r0, p.r1 = r1, p.n0 = n0, p.n1 = n1;
  p.slope = (n1 - n0) / (r1 - r0);
  return p;
}

// The pieces in increasing r, gaps filled with zero pieces; nothing for the
// distributions that have an analytic continuation of their own, and for a
// truncated log-normal unless `truncated_log_normal`.
inline std::optional<std::vector<Piece>> pieces_of(const SizeDistribution& d, bool truncated_log_normal) {
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
// of short straight pieces (a table's rows, by product integration), on the
// leg up from breakpoint `index`, or on the line or the shared leg of leg
// window `index` (LegWindow).
enum class Where { path, span, leg, line, anchor };

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
// 39,525 -> 12,431 at 200 nm with the 31-point rule against the 15-point one
// on panels 40 wide.
constexpr double kLongPiecePanels = 4;
constexpr int kLongPieceKronrodPoints = 61;
// The ripple that height H leaves of S(0) on such a piece has the period
// pi / (Re m - 1) in x (the interference of the central ray with the
// diffracted wave, 2 x (m - 1) in phase, van de Hulst 1957 Sec. 11.22).  A
// Gauss-Kronrod rule resolves a number of its periods per panel set by its
// Gauss part and fails abruptly beyond: the 31-point rule ~5 (water at 1e-9:
// 5.3 pass at 550 nm, 6.3 fail at 200 nm), the 61-point rule ~13 (14 fail
// in part at 1.55 um, 15 everywhere: the evaluations double).  Per period
// the 61-point rule needs fewer nodes (its Gauss part nearer the two per
// period of the asymptotic limit), and 61 nodes fill four batches of sixteen
// S(0) series where 41 or 51 leave 7 or 13 lanes idle.  So the first panels
// span 12 periods, no fewer than 40 units of x, nor more than 160 (absorbing
// drops, whose ripple is damped).  Measured at 1e-9, bins of 0.5-1 mm and
// of 0.1-0.5 + 0.5-1 mm (bulk_optics_speed bins), evaluations:
//   rule, periods   200 nm          550 nm         1.55 um       10.6 um
//   31, 5           12,333 / 22,188  3,962 / 7,029  1,482 / 2,595  304 / 487
//   41, 7           11,753 / 21,150  3,747 / 6,677
//   51, 9           11,370 / 20,436  3,648 / 6,462
//   61, 12          10,215 / 18,357  3,291 / 5,852  (see below)
// and the wall time of the two bins at 550 nm 0.109 -> 0.093 s (41 and 51:
// 0.117, 0.125 s, their idle lanes).
constexpr double kLongPieceRipplePeriods = 12;
constexpr double kLongPieceMaxWidths = 4;
// Runs of a table's short rows are integrated in spans by product
// integration with the 31-point rule (product_rule.hpp), whose interpolant
// is exact to degree 30 rather than the rule's 46: panels start at this
// fraction of panel_width.
constexpr double kSpanPanelWidths = 0.5;
constexpr int kSpanKronrodPoints = 31;
// A leg window (LegWindow) spans at most this many times its line's height,
// and its line costs about this many 15-point leg panels.  Measured at 1e-9 on
// a 10,000-row log-normal fog table at 550 nm with 15-point panels on the
// axis (373,881 evaluations without windows): widths 2, 4, 8, 16 take
// 267,895, 221,406, 190,334, 177,697 evaluations, the reported error 6.4,
// 6.3, 6.8, 11.6e-12 1/m (the line's |K - G| grows beyond 8: its panel then
// sees poles at a sixteenth of its width).  The axis panels in sqrt(y) leave
// the windows as they were (their height c is sized the same way).
constexpr double kWindowWidths = 8;
constexpr int kLinePanels = 2;

// A piece whose path spans kLongPiecePanels panels or more (k: the wave number).
inline bool long_piece(const Piece& p, double k, const SegmentedContourSettings& s) {
  return k * (p.r1 - p.r0) >= kLongPiecePanels * s.panel_width;
}
// Pieces whose path is taken in spans (span_panel): a table's short rows.
inline bool spanned_piece(const Piece& p, double k, const SegmentedContourSettings& s) {
  return !p.curved() && !long_piece(p, k, s);
}
// The end of the run of spanned pieces from piece i (i itself if it is not
// spanned): a span needs two of them or more (path_tasks, leg_windows and the
// cost estimate take the same runs).
template <class Spanned>
std::size_t run_end(std::size_t i, std::size_t pieces, const Spanned& spanned) {
  std::size_t end = i;
  while (end < pieces && spanned(end)) ++end;
  return end;
}

// |S(0)| on the real axis: <= 1/2 sum (2n+1)(|a_n| + |b_n|) <= (N + 1)^2, the
// series cut where Wiscombe's (1980) criterion ends it.
inline double forward_amplitude_bound(double x) {
  const double terms = x + 4.05 * std::cbrt(x) + 2;
  return (terms + 1) * (terms + 1);
}

// Breakpoints first ... last of a run of rows whose legs rise only to
// `height` and are joined there (segmented_contour.hpp, "Leg windows"): by
// Cauchy, each leg's part above the line Im x = height moves to the shared
// leg at x = anchor, along the line and along the path, so the path's density
// switches at the anchor for all of them.
struct LegWindow {
  std::size_t first = 0, last = 0;  // breakpoints, inclusive
  double anchor = 0, height = 0;    // in x
  // The window's differences summed, about r = anchor / k: D(r) = jump + slope (r - anchor / k).
  double jump = 0, slope = 0;
};

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
        axis_rule_(detail::make_rule<kAxisNodes>()),
        span_rule_(detail::rule_for(std::max(s.kronrod_points, kSpanKronrodPoints))),
        arithmetic_(arithmetic) {
    set_windows({});
  }

  // The leg windows (none: every leg rises to the path), and the points
  // where the path's density switches from one piece to the next that follow.
  void set_windows(std::vector<LegWindow> windows) {
    windows_ = std::move(windows);
    switch_x_.clear();
    switch_piece_.clear();
    std::size_t w = 0;
    for (std::size_t k = 0; k < pieces_.size(); ++k) {
      if (w < windows_.size() && k >= windows_[w].first) {
        if (k == windows_[w].first) switch_x_.push_back(windows_[w].anchor), switch_piece_.push_back(windows_[w].last);
        if (k == windows_[w].last) ++w;
        continue;
      }
      switch_x_.push_back(x_at(k)), switch_piece_.push_back(k);
    }
    switch_x_.push_back(x_at(pieces_.size()));
    for (LegWindow& lw : windows_) {
      lw.jump = lw.slope = 0;
      for (std::size_t k = lw.first; k <= lw.last; ++k) {
        double jump = 0, slope_change = 0;
        difference_at(k, jump, slope_change);
        lw.jump += jump + slope_change * (lw.anchor - x_at(k)) / k_;
        lw.slope += slope_change;
      }
    }
  }
  const std::vector<LegWindow>& windows() const { return windows_; }

  std::size_t breakpoints() const { return pieces_.size() + 1; }
  double x_at(std::size_t k) const { return k_ * (k < pieces_.size() ? pieces_[k].r0 : pieces_.back().r1); }
  bool zero_piece(std::size_t i) const { return pieces_[i].zero(); }
  double height(double t) const { return s_.height * std::tanh(s_.angle * t / s_.height); }
  // The path x(t) = t + i h(t) and its tangent x'(t).
  Complex path_point(double t) const { return {t, height(t)}; }
  Complex path_tangent(double t) const {
    const double c = 1 / std::cosh(s_.angle * t / s_.height);
    return {1.0, s_.angle * c * c};
  }

  // The jump and the change of slope (both in SI, the slope per metre) of
  // the density at breakpoint k, right minus left.
  void difference_at(std::size_t k, double& jump, double& slope_change) const {
    ATTENUVIS_CHECK_LT(k, breakpoints());
    const Difference d = segmented::difference_at(pieces_, k, x_at(k) / k_);
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
  bool long_piece(std::size_t i) const { return segmented::long_piece(pieces_[i], k_, s_); }
  bool spanned_piece(std::size_t i) const { return segmented::spanned_piece(pieces_[i], k_, s_); }
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
    Panel p;
    p.where = Where::path;
    p.index = i;
    p.quad = detail::evaluate_path_panel(
        path_rule(i), a, b, [&](double t) { return path_point(t); },
        [&](double t) { return path_tangent(t); },
        [&](Complex x) { return scale_ * piece.at(x / k_); }, m_, arithmetic_);
    return p;
  }

  // The path over [a, b] in t across the spanned pieces there: their
  // straight densities continued to the path do not join (they differ by
  // slope change x i h at each breakpoint), so the panel integrates each
  // piece's line against the interpolant of S(0) (product_rule.hpp).
  Panel span_panel(double a, double b) const {
    const double centre = 0.5 * (a + b);
    std::vector<detail::ProductRule::Segment> segments;
    std::size_t i =
        static_cast<std::size_t>(std::upper_bound(switch_x_.begin(), switch_x_.end(), a) - switch_x_.begin());
    for (i = i > 0 ? i - 1 : 0; i + 1 < switch_x_.size() && switch_x_[i] < b; ++i) {
      const Piece& piece = pieces_[switch_piece_[i]];
      ATTENUVIS_CHECK(!piece.curved());
      // scale n(x / k) = scale (n0 + slope (x / k - r0)), about x = centre.
      const double alpha = scale_ * (piece.n0 + piece.slope * (centre / k_ - piece.r0));
      segments.push_back({std::max(a, switch_x_[i]), std::min(b, switch_x_[i + 1]), alpha, scale_ * piece.slope / k_});
    }
    Panel p;
    p.where = Where::span;
    p.quad = detail::evaluate_product_panel(
        span_rule_, a, b, segments, [&](double t) { return path_point(t); },
        [&](double t) { return path_tangent(t); },
        m_, arithmetic_);
    return p;
  }

  // The line of leg window w over [a, b] in x at its height: each of its
  // breakpoints' difference D_k from x_k to the anchor (rightwards left of
  // it, leftwards right of it, hence the sign), product-integrated.
  Panel line_panel(std::size_t w, double a, double b) const {
    const LegWindow& lw = windows_[w];
    const double centre = 0.5 * (a + b), y = lw.height;
    std::vector<detail::ProductRule::Segment> segments;
    const auto add = [&](double lo, double hi, Complex alpha, Complex beta) {
      lo = std::max(lo, a), hi = std::min(hi, b);
      if (hi > lo) segments.push_back({lo, hi, alpha, beta});
    };
    const auto difference = [&](std::size_t k, Complex& alpha, Complex& beta) {  // D_k about centre, in x
      double jump = 0, slope_change = 0;
      difference_at(k, jump, slope_change);
      alpha += scale_ * (jump + slope_change * (centre - x_at(k)) / k_);
      beta += scale_ * slope_change / k_;
    };
    Complex alpha{}, beta{};
    for (std::size_t k = lw.first; k <= lw.last && x_at(k) < lw.anchor; ++k) {
      difference(k, alpha, beta);
      add(x_at(k), std::min(lw.anchor, k < lw.last ? x_at(k + 1) : lw.anchor), alpha, beta);
    }
    alpha = beta = 0;
    for (std::size_t k = lw.last; k >= lw.first && x_at(k) > lw.anchor; --k) {
      difference(k, alpha, beta);
      add(std::max(lw.anchor, k > lw.first ? x_at(k - 1) : lw.anchor), x_at(k), -alpha, -beta);
      if (k == 0) break;
    }
    Panel p;
    p.where = Where::line;
    p.index = w;
    p.quad = detail::evaluate_product_panel(
        span_rule_, a, b, segments, [&](double t) { return Complex(t, y); }, [](double) { return Complex(1, 0); },
        m_, arithmetic_);
    return p;
  }

  // The shared leg of window w over y in [a, b] (above its line).
  Panel anchor_panel(std::size_t w, double a, double b) const {
    const LegWindow& lw = windows_[w];
    const double r_anchor = lw.anchor / k_;
    Panel p;
    p.where = Where::anchor;
    p.index = w;
    p.quad = detail::evaluate_path_panel(
        rule_, a, b, [&](double y) { return Complex(lw.anchor, y); }, [](double) { return Complex(0, 1); },
        [&](Complex x) { return scale_ * (lw.jump + lw.slope * (x / k_ - r_anchor)); }, m_, arithmetic_);
    return p;
  }

  // The weight of leg k: scale D_k(x / k) (segmented_contour.hpp).  Straight
  // pieces: the difference written as jump + slope change x (r - r_k), which
  // is exactly 0 on the axis of a continuous table.
  auto leg_weight(std::size_t k) const {
    const Piece* right = k < pieces_.size() ? &pieces_[k] : nullptr;
    const Piece* left = k > 0 ? &pieces_[k - 1] : nullptr;
    double jump = 0, slope_change = 0;
    difference_at(k, jump, slope_change);
    const bool straight = !(right && right->curved()) && !(left && left->curved());
    return [=, scale = scale_, wave_number = k_, rk = x_at(k) / k_](Complex x) {
      const Complex r = x / wave_number;
      if (straight) return scale * (jump + slope_change * (r - rk));
      return scale * ((right ? right->at(r) : Complex{}) - (left ? left->at(r) : Complex{}));
    };
  }

  // The leg up from breakpoint k over y in [a, b]: i int D_k(x_k + i y) dy.
  Panel leg_panel(std::size_t k, double a, double b) const {
    Panel p;
    if (sqrt_axis_panel(a)) {
      axis_panels(&k, &b, 1, &p);
      return p;
    }
    p.where = Where::leg;
    p.index = k;
    const double xk = x_at(k);
    p.quad = detail::evaluate_path_panel(
        rule_, a, b, [&](double y) { return Complex(xk, y); }, [](double) { return Complex(0, 1); }, leg_weight(k),
        m_, arithmetic_);
    if (a == 0) p.near_axis = near_axis_bound(k, lowest_node(b));
    return p;
  }

  // Whether a leg's panel from y = a up is on the axis and taken in sqrt(y).
  bool sqrt_axis_panel(double a) const { return a == 0 && s_.sqrt_axis_panels; }

  // Legs whose panels on the axis are evaluated together (axis_panels), and
  // the nodes of each (the 7-point rule in sqrt(y)).
  static constexpr std::size_t kAxisGroup = 16, kAxisNodes = 7;

  // The panels on the axis [0, b[i]] of legs k[i], i < count <= kAxisGroup,
  // in sqrt(y), y = b t^2, dy = 2 b t dt (segmented_contour.hpp, "The panel
  // on the axis"): their 7 count S(0) in one call.  Sixteen legs' 112 points
  // fill seven batches of sixteen series (forward_amplitude.cpp), where one
  // leg alone fills seven lanes of eight and two legs fourteen of sixteen.
  void axis_panels(const std::size_t* k, const double* b, std::size_t count, Panel* out) const {
    ATTENUVIS_CHECK(count <= kAxisGroup);
    const detail::OrderedNodes nodes = detail::ordered_nodes(axis_rule_);
    const std::size_t n = kAxisNodes;
    ATTENUVIS_CHECK(nodes.u.size() == n);
    std::array<Complex, kAxisNodes * kAxisGroup> x;
    std::array<mie::ForwardAmplitude, kAxisNodes * kAxisGroup> fa;
    for (std::size_t i = 0; i < count; ++i) {
      const double xk = x_at(k[i]), height = b[i];
      detail::path_points(nodes, 0.0, 1.0, [&](double t) { return Complex(xk, height * t * t); }, &x[i * n]);
    }
    mie::forward_amplitudes(x.data(), count * n, m_, arithmetic_, fa.data());
    for (std::size_t i = 0; i < count; ++i) {
      const double height = b[i];
      Panel& p = out[i];
      p.where = Where::leg;
      p.index = k[i];
      p.quad = detail::path_panel_sums(
          nodes, 0.0, 1.0, &x[i * n], &fa[i * n], [&](double t) { return Complex(0, 2 * height * t); },
          leg_weight(k[i]));
      p.quad.a = 0, p.quad.b = height;
      p.near_axis = near_axis_bound(k[i], lowest_node(height));
    }
  }

  // Below the lowest node y_1 of a leg's panel on the axis the rule sees
  // nothing of a resonance lying closer to the axis; that part is bounded
  // (segmented_contour.hpp).  A power law's or a log-normal's slope varies
  // along the leg: twice the slope at r_k covers it for y_1 << x_k (for the
  // log-normal, y_1 << x_k / (1 + |z_k| / s): n'' / n' ~ (1 + |z| / s) / r).
  double lowest_node(double height) const {
    if (!s_.sqrt_axis_panels) return lowest_node_in_y(height);
    const double t1 = 0.5 * (1 - axis_rule_.abscissa.back());
    return height * t1 * t1;
  }
  // The lowest node of the settings' rule on [0, height] in y, which sizes
  // the panel on the axis either way (axis_cut).
  double lowest_node_in_y(double height) const { return 0.5 * height * (1 - rule_.abscissa.back()); }
  // The near-axis bound at one breakpoint as a function of y_1 (segmented_contour.hpp):
  // 2 scale S_max e^{2 y_1} (|J| y_1 + slope y_1^2 / (2 k)), with what does
  // not depend on y_1 taken once.
  struct NearAxisBound {
    double factor, jump, kink;  // 2 scale S_max, |J|, slope / (2 k)

    double operator()(double y1) const {
      const double t = 2 * y1;
      return factor * growth(t) * (jump * y1 + kink * y1 * y1);
    }
    // The y_1 in [lo, hi] where the bound equals `allowed`, given that it is
    // below at lo and above at hi: Newton's method from the root without
    // the growth factor (>= 1, so that root lies above), or from hi.  The
    // bound is increasing and convex in y_1, so the steps fall monotonically
    // onto the root; they stop when one moves y_1 by less than 1e-7 of
    // itself (it only sizes a panel).
    double root(double allowed, double lo, double hi) const {
      const double c = allowed / factor;  // kink y^2 + jump y = c, the stable root
      double y = std::min(hi, 2 * c / (jump + std::sqrt(jump * jump + 4 * kink * c)));
      for (int i = 0; i < 60; ++i) {
        const double t = 2 * y, q = jump * y + kink * y * y;
        const double slope = factor * (2 * growth_slope(t) * q + growth(t) * (jump + 2 * kink * y));
        const double step = ((*this)(y) - allowed) / slope;
        if (!(step > 0)) break;
        y = std::max(lo, y - step);
        if (step <= 1e-7 * y) break;
      }
      return y;
    }

   private:
    // e^t <= 1 + t + t^2 for 0 <= t <= 1 (the rest of the series is at most
    // (e - 2) t^2); y_1 < 0.02 here (a lowest node below heights <= 4), and
    // exp was most of the time of the legs' cuts.
    static double growth(double t) { return t <= 1 ? 1 + t + t * t : std::exp(t); }
    static double growth_slope(double t) { return t <= 1 ? 1 + 2 * t : std::exp(t); }
  };
  NearAxisBound near_axis_bound_of(std::size_t k) const {
    double jump = 0, slope_change = 0;
    difference_at(k, jump, slope_change);
    const double slope = (curved_at(k) ? 2.0 : 1.0) * std::abs(slope_change);
    return {2 * scale_ * forward_amplitude_bound(x_at(k)), std::abs(jump), slope / (2 * k_)};
  }
  double near_axis_bound(std::size_t k, double y1) const { return near_axis_bound_of(k)(y1); }
  // Where to cut a leg's panel [0, b] on the axis so that the lower part's
  // bound, were its rule the settings' in y, is about `allowed`: between
  // b kLowestCut and `largest` (the upper part is split again at its middle
  // if its |K - G| asks).  The rule in sqrt(y) charges 11 to 120 times less.
  static constexpr double kLowestCut = 1.0 / 4096;
  double axis_cut(std::size_t k, double b, double allowed, double largest) const {
    return axis_cut_between(k, b * kLowestCut, largest, allowed);
  }
  // The same cut searched between lo and hi (at lo if the bound there is
  // still above `allowed`).  The lowest node is proportional to the height.
  double axis_cut_between(std::size_t k, double lo, double hi, double allowed) const {
    const NearAxisBound bound = near_axis_bound_of(k);
    const double node_per_height = lowest_node_in_y(1.0);
    const double y_lo = node_per_height * lo, y_hi = node_per_height * hi;
    if (bound(y_hi) <= allowed) return hi;
    if (bound(y_lo) > allowed) return lo;
    return std::clamp(bound.root(allowed, y_lo, y_hi) / node_per_height, lo, hi);
  }

  Panel evaluate(Where where, std::size_t index, double a, double b) const {
    throw_if_cancelled(s_.cancel);  // once per panel: kronrod_points Mie evaluations
    switch (where) {
      case Where::path: return path_panel(index, a, b);
      case Where::span: return span_panel(a, b);
      case Where::line: return line_panel(index, a, b);
      case Where::anchor: return anchor_panel(index, a, b);
      case Where::leg: break;
    }
    return leg_panel(index, a, b);
  }

 private:
  std::vector<Piece> pieces_;
  double k_, scale_;
  Complex m_;
  const SegmentedContourSettings& s_;
  detail::Rule rule_, long_rule_, axis_rule_;
  detail::ProductRule span_rule_;
  mie::Precision arithmetic_;
  std::vector<LegWindow> windows_;
  // The path's density is piece switch_piece_[i] from switch_x_[i] to
  // switch_x_[i + 1]: the breakpoints, or a window's anchor for its breakpoints.
  std::vector<double> switch_x_;
  std::vector<std::size_t> switch_piece_;
};
}  // namespace attenuvis::weather::detail::segmented
