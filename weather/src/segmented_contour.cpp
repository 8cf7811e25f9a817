// sigma_ext of a table or a power law by Cauchy's theorem on each of its
// pieces: see segmented_contour.hpp.
#include "attenuvis/weather/segmented_contour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "attenuvis/io/number_text.hpp"
#include "segmented_integrand.hpp"

namespace attenuvis::weather {
using io::significant;
namespace {
using namespace detail::segmented;

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
    const std::size_t end = run_end(i, pieces, [&](std::size_t j) { return f.spanned_piece(j); });
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
// x), so the path alone sizes their near-axis budget: the bound below each
// leg's lowest node is a quarter of its share of the tolerance.
double leg_allowed(const Integrand& f, const std::vector<Panel>& path, const SegmentedContourSettings& s) {
  Complex path_total{};
  for (const auto& p : path) path_total += p.quad.kronrod;
  return 0.25 * s.rel_tolerance * std::abs(path_total.real()) / std::max<std::size_t>(leg_count(f), 1);
}

// Where each leg's first panel [0, c] ends: the bound below its lowest node
// is `allowed` (infinity where the leg vanishes).  Each cut is a root search
// of its own (4 % of a run over 10^5 rows on one core when they were
// bisections): shared out like the panels.
std::vector<double> axis_cuts(const Integrand& f, double allowed) {
  std::vector<double> c(f.breakpoints(), std::numeric_limits<double>::infinity());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.breakpoints(), 1024), [&](const auto& range) {
    for (std::size_t kb = range.begin(); kb < range.end(); ++kb) {
      if (f.leg_vanishes(kb)) continue;
      const double h = f.height(f.x_at(kb));
      c[kb] = f.axis_cut(kb, h, allowed, h);
    }
  });
  return c;
}

// Panels of a leg graded by 16 from c up to h: [c, 16c], [16c, 256c], ...
int graded_panels(double c, double h) { return c < h ? static_cast<int>(std::ceil(std::log(h / c) / std::log(16.0))) : 0; }

// Leg windows over the runs of rows: consecutive breakpoints within
// kWindowWidths line heights, the height the smallest of their first cuts
// (so that [0, height] is each one's first panel), where one 31-point line
// panel and one shared leg cost fewer panels than the legs' graded upper
// parts.  Dense tables only: rows farther apart than the cut keep their legs.
std::vector<LegWindow> leg_windows(const Integrand& f, const std::vector<double>& cut) {
  std::vector<LegWindow> windows;
  const std::size_t pieces = f.breakpoints() - 1;
  for (std::size_t run = 0; run < pieces; ++run) {
    const std::size_t end = run_end(run, pieces, [&](std::size_t j) { return f.spanned_piece(j); });
    if (end < run + 2) continue;
    // Interior breakpoints run + 1 ... end - 1; a vanishing leg's cut is infinite.
    std::vector<int> panels(end - run);  // each leg's now, at breakpoint run + i
    for (std::size_t i = run + 1; i < end; ++i)
      panels[i - run] = std::isfinite(cut[i]) ? 1 + graded_panels(cut[i], f.height(f.x_at(i))) : 0;
    for (std::size_t i = run + 1; i < end;) {
      if (!std::isfinite(cut[i])) { ++i; continue; }
      double height = cut[i];
      std::size_t last = i, legs = 1;
      int now = panels[i - run];
      for (std::size_t n = i + 1; n < end; ++n) {
        const double h = std::min(height, cut[n]);
        if (f.x_at(n) - f.x_at(i) > kWindowWidths * h) break;
        height = h, last = n;
        if (std::isfinite(cut[n])) ++legs, now += panels[n - run];
      }
      const double anchor = 0.5 * (f.x_at(i) + f.x_at(last));
      const int windowed = static_cast<int>(legs) + kLinePanels + graded_panels(height, f.height(anchor));
      if (legs >= 3 && windowed < now) {
        windows.push_back({i, last, anchor, height});
        i = last + 1;
      } else {
        ++i;
      }
    }
    run = end - 1;
  }
  return windows;
}

// Each leg as panels [0, c], [c, 16c], [16c, 256c], ..., h; a windowed leg
// as [0, height] alone, and each window's line and shared leg (graded from
// its height up to the path).
std::vector<Task> leg_tasks(const Integrand& f, const std::vector<double>& cut) {
  std::vector<Task> tasks;
  const auto& windows = f.windows();
  std::size_t w = 0;
  for (std::size_t kb = 0; kb < f.breakpoints(); ++kb) {
    while (w < windows.size() && windows[w].last < kb) ++w;
    if (f.leg_vanishes(kb)) continue;
    if (w < windows.size() && kb >= windows[w].first) {
      tasks.push_back({Where::leg, kb, 0.0, windows[w].height});
      continue;
    }
    const double h = f.height(f.x_at(kb));
    double c = cut[kb];
    tasks.push_back({Where::leg, kb, 0.0, c});
    for (; c < h; c *= 16) tasks.push_back({Where::leg, kb, c, std::min(16 * c, h)});
  }
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const LegWindow& lw = windows[i];
    tasks.push_back({Where::line, i, f.x_at(lw.first), f.x_at(lw.last)});
    const double h = f.height(lw.anchor);
    for (double c = lw.height; c < h; c *= 16) tasks.push_back({Where::anchor, i, c, std::min(16 * c, h)});
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

  // Legs' panels on the axis in groups (one call of S(0) for all:
  // Integrand::axis_panels), in task order; the others one by one.
  std::vector<Panel> evaluate_all(const std::vector<Task>& ts) {
    std::vector<Panel> out(ts.size());
    std::vector<std::size_t> axis, single;
    for (std::size_t i = 0; i < ts.size(); ++i)
      (ts[i].where == Where::leg && f_.sqrt_axis_panel(ts[i].a) ? axis : single).push_back(i);
    constexpr std::size_t group = Integrand::kAxisGroup;
    const std::size_t groups = (axis.size() + group - 1) / group;
    tbb::parallel_for(std::size_t(0), single.size() + groups, [&](std::size_t u) {
      if (u < single.size()) {
        const Task& t = ts[single[u]];
        out[single[u]] = f_.evaluate(t.where, t.index, t.a, t.b);
        return;
      }
      throw_if_cancelled(s_.cancel);
      const std::size_t first = group * (u - single.size()), count = std::min(group, axis.size() - first);
      std::array<std::size_t, group> k;
      std::array<double, group> b;
      std::array<Panel, group> panels;
      for (std::size_t i = 0; i < count; ++i) k[i] = ts[axis[first + i]].index, b[i] = ts[axis[first + i]].b;
      f_.axis_panels(k.data(), b.data(), count, panels.data());
      for (std::size_t i = 0; i < count; ++i) out[axis[first + i]] = panels[i];
    });
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
                        std::size_t legs, std::size_t windows, bool spans, bool verify, mie::Precision arithmetic,
                        std::size_t evaluations, double x_max) {
  std::ostringstream method;
  method << "segmented contour: Cauchy on each of " << pieces << " pieces of the "
         << (std::holds_alternative<PowerLaw>(d.form())  ? "power law"
             : std::holds_alternative<LogNormal>(d.form()) ? "cut log-normal"
                                                            : "table")
         << ", path x = t + i h(t), h <= " << significant(s.height, 3) << ", with " << legs
         << " legs down to the breakpoints"
         << (windows ? " (those of dense rows joined above the axis in " + std::to_string(windows) + " windows)" : "")
         << ", near-axis parts bounded (segmented_contour.hpp), Gauss-Kronrod "
         << s.kronrod_points << " (Boost.Math; on pieces spanning " << kLongPiecePanels << " panels or more, "
         << std::max(s.kronrod_points, kLongPieceKronrodPoints)
         << (s.sqrt_axis_panels ? "; legs' panels on the axis, 7 in sqrt(y)" : "") << ")"
         << (spans ? ", short rows' path in spans across them by product integration" : "")
         << (verify ? ", verified by halving" : "")
         << ", S(0) in "
         << (arithmetic == mie::Precision::double_precision ? "double" : "long double") << ", rel. tol "
         << significant(s.rel_tolerance, 3) << ", " << evaluations << " evaluations, x <= " << significant(x_max, 3);
  return method.str();
}

// Evaluations per unit of x on a long piece's path, per short piece, and
// per unit of x and at least on a span of short rows (10,000 log-normal rows
// at 550 nm: the path's spans ~1,400 evaluations); a panel on the axis (7
// points, sixteen legs' in seven full batches), one above it, a window's
// line; and the CPU cost of one evaluation
// (validation/bench/forward_amplitude_speed: 0.8-0.9 us at x = 100, 40-46 us
// at 1e4), from the runs quoted in segmented_contour.hpp, rounded up.
constexpr double kEvaluationsPerX = 0.7, kEvaluationsPerSpanX = 2, kEvaluationsPerSpan = 31;
constexpr double kEvaluationsPerAxisPanel = 7, kEvaluationsPerLegPanel = 15, kEvaluationsPerLine = 31 * kLinePanels;
constexpr double kSecondsPerTerm = 5e-9, kSecondsPerEvaluation = 0.45e-6;

// sigma_ext with Q_ext = 2 (the pieces at their middles): the scale of the
// legs' budget before the path's sum is known.
double geometric_extinction(const std::vector<Piece>& pieces) {
  double sum = 0;
  for (const Piece& p : pieces) {
    const double r = 0.5 * (p.r0 + p.r1);
    sum += 2 * kPi * r * r * std::abs(p.value_at(r)) * (p.r1 - p.r0);
  }
  return sum;
}

// The legs as the run will take them: cut where their near-axis bound meets
// the budget (found as deep as it lies: the run splits a panel whose bound
// stays above it), graded by 16 up to the path, or windowed.  The bound
// holds for any passive sphere, so the index does not enter.
template <class Add>
void add_legs(std::vector<Piece> pieces, double wavelength_m, const SegmentedContourSettings& s, const Add& add) {
  const double sigma = geometric_extinction(pieces);
  const Complex any_index(1.5, 0);  // never evaluated: the estimate needs no S(0)
  Integrand f(std::move(pieces), wavelength_m, any_index, s, mie::Precision::double_precision);
  const std::size_t legs = leg_count(f);
  if (legs == 0 || !(sigma > 0)) return;
  const double allowed = 0.25 * s.rel_tolerance * sigma / static_cast<double>(legs);
  const std::vector<double> cut = axis_cuts(f, allowed);
  const std::vector<LegWindow> windows = s.spans ? leg_windows(f, cut) : std::vector<LegWindow>{};
  std::size_t w = 0;
  for (std::size_t kb = 0; kb < f.breakpoints(); ++kb) {
    while (w < windows.size() && windows[w].last < kb) ++w;
    if (f.leg_vanishes(kb)) continue;
    const double x = f.x_at(kb), h = f.height(x);
    if (w < windows.size() && kb >= windows[w].first) {
      add(kEvaluationsPerAxisPanel, x);
      continue;
    }
    const bool clamped = cut[kb] <= h * Integrand::kLowestCut;
    const double deepest = clamped ? f.axis_cut_between(kb, h * 0x1p-48, h, allowed) : cut[kb];
    add(kEvaluationsPerAxisPanel + kEvaluationsPerLegPanel * graded_panels(deepest, h), x);
  }
  for (const LegWindow& lw : windows)
    add(kEvaluationsPerLine + kEvaluationsPerLegPanel * graded_panels(lw.height, f.height(lw.anchor)), lw.anchor);
}

// One run of the route over `pieces` with S(0) in `arithmetic`; `spent`:
// the evaluations of an earlier run, counted in the result.
ContourExtinction route_in(std::vector<Piece> pieces, const SizeDistribution& d, double wavelength_m, Complex m,
                           const SegmentedContourSettings& s, mie::Precision arithmetic, double x_max,
                           std::size_t spent) {
  Integrand f(std::move(pieces), wavelength_m, m, s, arithmetic);

  // The path first, then the legs, whose budget the path's sum sets; where
  // rows are dense, leg windows, and the spans again with the density
  // switching at their anchors.
  PieceQuadrature quadrature(f, d, s);
  const std::vector<Task> path = path_tasks(f, s);
  const bool spans = std::any_of(path.begin(), path.end(), [](const Task& t) { return t.where == Where::span; });
  std::vector<Panel> panels = quadrature.evaluate_all(path);
  const std::vector<double> cut = axis_cuts(f, leg_allowed(f, panels, s));
  if (spans) {
    f.set_windows(leg_windows(f, cut));
    // Only the span panels across a window's breakpoints change.
    std::vector<std::size_t> moved;
    std::vector<Task> again;
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Task& t = path[i];
      if (t.where != Where::span) continue;
      for (const LegWindow& w : f.windows())
        if (t.a < f.x_at(w.last) && t.b > f.x_at(w.first)) {
          moved.push_back(i), again.push_back(t);
          break;
        }
    }
    std::vector<Panel> redone = quadrature.evaluate_all(again);
    for (std::size_t r = 0; r < moved.size(); ++r) panels[moved[r]] = std::move(redone[r]);
  }
  for (Panel& p : quadrature.evaluate_all(leg_tasks(f, cut))) panels.push_back(std::move(p));
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
  out.evaluations = spent + quadrature.evaluations();
  out.max_size_parameter = x_max;
  out.height = s.height;
  out.angle = s.angle;
  out.verified = verify;
  out.method = method_text(d, s, f.breakpoints() - 1, leg_count(f), f.windows().size(), spans, verify, arithmetic,
                           out.evaluations, x_max);
  return out;
}

}  // namespace

namespace {
// The estimate over pieces already taken from the distribution.
ContourCost cost_of(std::vector<Piece> pieces, double wavelength_m, const SegmentedContourSettings& s) {
  ContourCost cost;
  const double k = 2 * kPi / wavelength_m;
  auto add = [&](double evaluations, double x) {
    cost.evaluations += evaluations;
    cost.seconds += evaluations * (kSecondsPerEvaluation + kSecondsPerTerm * x);
  };
  // As path_tasks: runs of two or more short straight pieces in spans.
  const auto spanned = [&](std::size_t i) { return spanned_piece(pieces[i], k, s); };
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::size_t end = run_end(i, pieces.size(), spanned);
    const Piece& p = pieces[i];
    if (s.spans && end >= i + 2) {
      const double xa = k * p.r0, xb = k * pieces[end - 1].r1;
      add(std::max(kEvaluationsPerSpan, (xb - xa) * kEvaluationsPerSpanX), 0.5 * (xa + xb));
      i = end - 1;
    } else if (!p.zero()) {
      const double xa = k * p.r0, xb = k * p.r1;
      add(std::max<double>(s.kronrod_points, (xb - xa) * kEvaluationsPerX), 0.5 * (xa + xb));
    }
  }
  add_legs(std::move(pieces), wavelength_m, s, add);
  return cost;
}
}  // namespace

ContourCost segmented_contour_cost(const SizeDistribution& d, double wavelength_m, const SegmentedContourSettings& s) {
  auto pieces = pieces_of(d, s.truncated_log_normal);
  return pieces ? cost_of(std::move(*pieces), wavelength_m, s) : ContourCost{};
}

std::optional<ContourExtinction> segmented_contour_extinction(const SizeDistribution& d, double wavelength_m,
                                                              Complex m, const SegmentedContourSettings& s) {
  auto pieces = pieces_of(d, s.truncated_log_normal);
  if (!pieces) return std::nullopt;
  const double k = 2 * kPi / wavelength_m;
  const double x_min = k * pieces->front().r0, x_max = k * pieces->back().r1;
  if (!(x_max <= s.max_x) || !(x_min > 0)) return std::nullopt;
  const ContourCost cost = cost_of(*pieces, wavelength_m, s);
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
  ContourExtinction out = route_in(*pieces, d, wavelength_m, m, run, arithmetic, x_max, 0);
  // Splitting panels does not lower the rounding bound.  It stays far below
  // the tolerance unless the legs carry contributions many times sigma_ext
  // that cancel (as at a table's steep steps, two kinks close together);
  // long double lowers it ~2000-fold, at ~10 times the time (scalar series
  // against sixteen on vectors: a 10^6-row table with such steps, 2.4 s
  // and 24 s), so the run is repeated in it if that stays within the limit.
  const auto over = [&] { return out.extinction.rounding_error > s.rel_tolerance * std::abs(out.extinction.value); };
  const double again_seconds = 10 * cost.seconds * static_cast<double>(out.evaluations) / std::max(cost.evaluations, 1.0);
  const bool again = over() && arithmetic == mie::Precision::double_precision && again_seconds <= s.max_seconds;
  if (again)
    out = route_in(std::move(*pieces), d, wavelength_m, m, run, mie::Precision::extended, x_max, out.evaluations);
  if (over())
    throw std::runtime_error(
        "sigma_ext by segmented contour over " + d.describe() + ": the rounding bound of S(0) (" +
        significant(out.extinction.rounding_error, 3) + " 1/m) exceeds the tolerance (" +
        significant(s.rel_tolerance * std::abs(out.extinction.value), 3) + " 1/m)" +
        (again ? " in long double"
               : " in double, and long double would take ~" + significant(again_seconds, 2) + " s of one core") +
        ": its legs carry contributions many times sigma_ext that cancel, as at a table's steep steps; smooth the "
        "table (more digits in its densities) or loosen the tolerance");
  return out;
}

}  // namespace attenuvis::weather
