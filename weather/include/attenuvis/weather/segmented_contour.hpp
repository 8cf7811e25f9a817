// Extinction of a piecewise-analytic size distribution (a table, a power law
// with bounds) by Cauchy's theorem on each piece.
//
// sigma_ext = sum_i int_{x_i}^{x_i+1} Re F_i(x) dx,  F_i(x) = (4 pi / k^3) S(0; x) n_i(x / k),
// x = k r, since Q_ext pi r^2 n dr = 4 Re S(0)/x^2 pi (x/k)^2 n dx/k.  Between two
// breakpoints the density of a table is a straight line n_i(r) = n0 + s_i (r - r_i)
// (size_distribution.hpp), of a power law c r^-nu (principal branch): both are
// analytic in Im r >= 0, and so is S(0) (mie/forward_amplitude.hpp).  Cauchy on
// each piece's rectangle [x_i, x_i+1] x [0, h] gives
//
//   int_{x_i}^{x_i+1} F_i = int_{L_i} F_i + int_{P_i} F_i - int_{L_i+1} F_i,
//
// L_k the vertical leg from x_k up to the path P: x(t) = t + i h(t),
// h(t) = H tanh(theta t / H) (the path of contour_extinction.hpp: low in the
// Rayleigh region, at height H where the resonances are damped), P_i its part
// over [x_i, x_i+1].  Summed over pieces:
//
//   sigma_ext = Re [ sum_i int_{P_i} F_i  +  sum_k i int_0^{h(x_k)} D_k(x_k + i y) dy ],
//   D_k = (4 pi / k^3) S(0) (n_k - n_{k-1}),  n_{-1} = n_N = 0 (outside the table).
//
// On a continuous table n_k - n_{k-1} = (s_k - s_{k-1}) (r - r_k): the leg's
// integrand vanishes on the axis, so the resonances just below it weigh like
// their width squared.  At a jump (a bin edge, a truncated end, a zero segment)
// the integrand is the full jump times S(0) on the axis.  Both are handled the
// same way: each leg is a run of Gauss-Kronrod panels graded towards the axis
// ([0, c], [c, 16c], ..., split further when the error asks), and what the
// rule of its lowest panel cannot see below its lowest node y_1 is bounded,
// not estimated:
//
//   |int_0^{y_1} D_k| <= (4 pi / k^3) S_max e^{2 y_1} (|J| y_1 + |s_k - s_{k-1}| y_1^2 / (2 k)),
//
// S_max = (N + 1)^2 >= |S(0)| on the real axis (a partial wave of a passive
// sphere scatters no more than it extinguishes, |a_n|^2 <= Re a_n, so
// |a_n|, |b_n| <= 1; N = x + 4.05 x^(1/3) + 2 terms, Wiscombe 1980), grown by
// e^{2 y} at most above it (the growth of the Mie terms, forward_amplitude.hpp);
// twice that is charged (the rule's own extrapolation over [0, y_1] as well) as
// the "resonance" error.
//
// The panel on the axis.  Its height c is where that bound, for the
// 15-point rule in y (y_1 = 0.0043 c), meets the leg's budget.  It is then
// integrated by the 7-point rule in t = sqrt(y / c): i int_0^1 D_k(x_k + i c t^2)
// 2 c t dt, still analytic and smooth in t, whose lowest node lies at
// y_1 = c (0.0198)^2 = 3.9e-4 c, eleven times nearer the axis, so the bound
// charged falls 11-fold at a jump and 120-fold at a kink (it grows like y_1
// and y_1^2).  Sixteen legs' seven nodes are evaluated together, seven full
// batches of sixteen S(0) series.  Sizing c by the lower node instead (11 times taller panels) fails
// the 7-point rule's |K - G|: 1.79 M evaluations on 10^5 rows against 0.74 M.
// Measured at 1e-9 on log-normal fog tables at 550 nm: 10^4 rows 190,024 ->
// 110,024 evaluations, 10^5 rows 1,544,461 -> 744,461, the reported error
// 6.8e-12 -> 2.7e-12 1/m (the near-axis part 4.5e-12 -> 3.8e-14).  The path over a long piece (a raindrop bin) or a
// curved one is Gauss-Kronrod panels that never cross a breakpoint (the
// density switches there, and off the axis its straight pieces do not join:
// they differ by (s_k - s_{k-1}) i h / k).  Over a run of short straight
// pieces (a table's rows) the path is one stretch of 31-point panels across
// the breakpoints, each integrating every row's own line against the
// polynomial that interpolates S(0) at its nodes (product integration,
// weather/src/product_rule.hpp; |K - G| from the Gauss nodes' interpolant):
// ~2 evaluations per unit of x instead of a panel per row.
//
// Leg windows.  Where rows lie closer together than the first cut c of their
// legs (a dense table), the parts of their legs above a common height
// y_w <= c are joined: by Cauchy on the rectangle between leg k and a shared
// leg at x = a_w (the anchor, amid the window's breakpoints),
//
//   int_{x_k + i y_w}^{x_k + i h} D_k = int_{x_k + i y_w}^{a_w + i y_w} D_k
//       + int_{a_w + i y_w}^{a_w + i h} D_k - int_{P: x_k -> a_w} D_k,
//
// so each leg keeps its near-axis panel [0, y_w] alone, the line Im x = y_w
// across the window carries sum_k D_k from each x_k to the anchor (a
// piecewise-linear weight: product integration again), one shared leg rises
// from the line to the path with sum_k D_k, and on the path the density
// switches from piece to piece at the anchor instead of at each breakpoint.
// A window spans at most 8 y_w in x and is taken where it costs fewer
// panels than the legs' upper parts (~7 evaluations per row instead of ~28).
//
// Reported error: sum |K - G| over every panel (path and legs), the near-axis
// bounds, the rounding bound of S(0) integrated along the path and legs
// (ForwardAmplitude::rounding_bound).  No tail: a table is zero outside its
// points.  When the ripple left at height H is not far below the tolerance
// (as contour_extinction.cpp), or when asked, every converged panel is split
// once and the change is charged too.
//
// Cost: a panel per piece or span and ~2 per leg (a piece spanning four
// panels or more, a raindrop bin, takes the 61-point rule: the ripple left at
// height H then needs a third of the 15-point rule's evaluations or fewer); a 200-point log-normal table in
// water at 550 nm takes 7,254 evaluations of S(0) at 1e-9, the analytic
// log-normal 625 (validation/bench/bulk_optics_speed table).  The near-axis
// bound, not the path, sets the cost: it stands 1e5-1e6 times above the actual
// error in tests/weather/test_segmented_contour.cpp.
#pragma once

#include <complex>
#include <cstddef>
#include <optional>

#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// The path and the tolerance of the segmented contour.
struct SegmentedContourSettings {
  double rel_tolerance = 1e-9;  // quadrature + near-axis + rounding, relative to sigma_ext
  double height = 4.0;          // H: the path's height in x above the real axis
  double angle = 0.25;          // theta: the path rises as h = theta x near x = 0
  double max_x = 1e5;           // forward_amplitude's range; cost ~ x_max^2 (see the estimate below)
  double panel_width = 40;      // initial path panels at most this wide in Re x
  int kronrod_points = 15;      // Gauss-Kronrod order of every panel (15, 21, 31, 41, 51, 61)
  // A table's runs of short rows in panels across their breakpoints, by
  // product integration (weather/src/product_rule.hpp); off: one panel per
  // row (the independent route of the tests).
  bool spans = true;
  // A leg's panel [0, c] on the axis by the 7-point Gauss-Kronrod rule in
  // t = sqrt(y / c) (half the evaluations, the lowest node 11 times nearer the
  // axis); off: the rule above in y (the independent route of the tests).
  bool sqrt_axis_panels = true;
  bool verify = false;          // split every converged panel once and charge the change
  // The budget of S(0) evaluations: at least this, and twice the estimate
  // (segmented_contour_cost) for a distribution whose estimate stays within
  // max_seconds of one core, which a table of many rows needs.
  std::size_t max_evaluations = 400000;
  double max_seconds = 5;       // refused up front when the estimate exceeds this (CPU seconds, one core)
  const std::atomic<bool>* cancel = nullptr;  // checked once per panel: Cancelled when set (cancel.hpp)
  // Also a log-normal cut at r_min, r_max: one analytic piece with a leg at
  // each cut.  Off by default, so that sigma() keeps the real axis for the
  // cut log-normals of Mie conditions; aerosols' sigma_ext takes it
  // (aerosol_optics.hpp), and the aerosol brute-force tests use it as the
  // independent sigma_ext where equispaced sums cannot resolve the resonances.
  bool truncated_log_normal = false;
};

// Nothing (no throw) when the route does not apply: the distribution is not a
// table or a power law, or it reaches beyond s.max_x; sigma() then takes the
// real axis (bulk_optics.hpp).  Throws std::runtime_error before any work
// when the estimate of segmented_contour_cost() exceeds s.max_seconds, and if
// the tolerance cannot be met within the budget (s.max_evaluations, or twice
// the estimate).  Splitting panels does not lower the rounding bound of
// S(0); where it exceeds the tolerance (legs many times sigma_ext that
// cancel, as at a table's steep steps) the run is repeated with S(0) in long
// double (~10 times the time) if that stays within s.max_seconds, and
// refused with both figures otherwise.
//
// Cost.  At height 4 the path's integrand still carries the ripple of S(0)
// of period pi/(Re m - 1) (~9.4 in x for water), damped to ~e^{-2 H (m-1)},
// which a 1e-9 tolerance must resolve: ~0.55 evaluations per unit of x on a
// long piece (the 61-point rule on panels twelve periods wide), each ~5 ns x x
// (the series has ~x terms, sixteen side by side); ~2 per unit of x over a
// table's rows (spans); a leg ~28 where a table's slope changes (~8 among
// dense rows: leg windows) and ~110 at a jump (a bin edge).
// Two bins of raindrops at 550 nm (0.1-0.5 and 0.5-1 mm: x up to 11,424) take
// 5,768 evaluations, 0.09 s on two cores, against a failure after 38 s on
// the real axis; fog-drop bins (x < 500) milliseconds.  A table of N rows of fog
// drops costs ~11 N evaluations at 1e4 rows and ~7.4 N at 1e5 (the legs'
// panels on the axis, one per row): ~0.65 s per 1e5 rows on two cores at
// 550 nm (~1.2 s of CPU); a table whose estimate exceeds max_seconds (about
// 5e5 such rows) is refused up front with the estimate, so that no run is
// silent for more than a few seconds.  The estimate cuts the legs as the run
// will (their near-axis bounds against a budget from Q_ext = 2) and forms the
// same windows: within 0.98-1.5 times the evaluations of log-normal tables
// of 10^3-10^5 rows, dense bins and raindrop bins from 200 nm to 10.6 um
// (0.6 times on 10^6 rows whose densities, given to three digits, make
// steep steps: the run then splits legs the estimate does not foresee).
// The result's resonance_error holds the near-axis bounds; tail_error is 0.
// The evaluations and CPU seconds (one core) the rule is estimated to take
// over `d` (0 for a distribution it does not apply to).
struct ContourCost {
  double evaluations = 0, seconds = 0;
};
ContourCost segmented_contour_cost(const SizeDistribution& d, double wavelength_m,
                                   const SegmentedContourSettings& s = {});

// sigma_ext of a tabulated or binned distribution by the segmented contour
// described above, or nullopt where the rule does not apply.
std::optional<ContourExtinction> segmented_contour_extinction(const SizeDistribution& d, double wavelength_m,
                                                              std::complex<double> m,
                                                              const SegmentedContourSettings& s = {});

}  // namespace attenuvis::weather
