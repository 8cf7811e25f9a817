// Error vs. run time of the bulk-optics quadrature settings.
#include "attenuvis/validation/quadrature_tradeoff.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <sstream>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/refractive_index.hpp"

namespace attenuvis::validation {

using namespace attenuvis::weather;

namespace {

// Best of `repeats` (at least one) wall times of f(), in ms.
template <class F>
double best_milliseconds(F&& f, int repeats) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < std::max(1, repeats); ++r) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return best;
}

// One distribution of the study at the study's wavelength and water index.
struct TradeoffCase {
  std::string name;  // e.g. "fog:radiation @ 550 nm"
  const SizeDistribution& d;
  double wavelength_m;
  std::complex<double> m;
  int repeats;
};

// Reference: the contour integral (contour_extinction.hpp), which resolves
// the resonances, at tolerance 1e-12 and tail 1e-16; its own error bound is
// in its row.  Empty when the contour integral gives no result.
std::optional<ContourExtinction> add_reference_row(const TradeoffCase& c, std::vector<QuadratureTradeoffRow>& rows) {
  ContourSettings ref;
  ref.rel_tolerance = 1e-12;
  ref.tail_fraction = 1e-16;
  ref.max_evaluations = 4000000;
  ref.verify = true;
  auto reference = contour_extinction(c.d, c.wavelength_m, c.m, ref);
  if (!reference) return reference;
  QuadratureTradeoffRow row;
  row.case_name = c.name + " (reference: contour h=4, tol 1e-12, verified by halving)";
  row.rel_tolerance = ref.rel_tolerance;
  row.kronrod_points = ref.kronrod_points;
  row.tail_fraction = ref.tail_fraction;
  row.sigma_per_m = reference->extinction.value;
  row.reported_quadrature_tail_error = reference->extinction.error();
  row.evaluations = reference->evaluations;
  rows.push_back(row);
  return reference;
}

// The contour rule (what sigma() uses) at its settings: heights 2, 4, 6 and
// tolerances 1e-6, 1e-9, 1e-12.
void add_contour_rows(const TradeoffCase& c, double reference, std::vector<QuadratureTradeoffRow>& rows) {
  for (double height : {2.0, 4.0, 6.0})
    for (double tol : {1e-6, 1e-9, 1e-12}) {
      ContourSettings s;
      s.rel_tolerance = tol;
      s.height = height;
      std::optional<ContourExtinction> r;
      QuadratureTradeoffRow row;
      row.milliseconds = best_milliseconds([&] { r = contour_extinction(c.d, c.wavelength_m, c.m, s); }, c.repeats);
      std::ostringstream label;
      label << c.name << " contour h=" << height;
      row.case_name = label.str();
      row.rel_tolerance = tol;
      row.kronrod_points = s.kronrod_points;
      row.tail_fraction = s.effective_tail_fraction();
      row.sigma_per_m = r->extinction.value;
      row.reported_quadrature_tail_error = r->extinction.error();
      row.actual_error = std::abs(r->extinction.value - reference);
      row.evaluations = r->evaluations;
      rows.push_back(row);
    }
}

// The real-axis rule (bulk_optics.hpp) over tolerances x Gauss-Kronrod
// orders x tail cuts.
void add_real_axis_rows(const TradeoffCase& c, double reference, std::vector<QuadratureTradeoffRow>& rows) {
  auto q = mie_efficiency_batch(c.m);  // what the bulk integrals use (sigma.cpp)
  for (double tol : {1e-6, 1e-9})
    for (int order : {15, 31})
      for (double tail : {0.0, 1e-6}) {
          QuadratureSettings s;
          s.rel_tolerance = tol;
          s.kronrod_points = order;
          s.tail_fraction = tail;
          s.max_evaluations = 2000000;
          QuadratureTradeoffRow row;
          row.case_name = c.name + " real axis";
          row.rel_tolerance = tol;
          row.kronrod_points = order;
          row.tail_fraction = tail > 0 ? tail : 1e-3 * tol;
          BulkOptics b;
          row.milliseconds =
              best_milliseconds([&] { b = integrate_bulk_optics(c.d, c.wavelength_m, q, s, c.m); }, c.repeats);
          row.sigma_per_m = b.extinction.value;
          row.reported_quadrature_tail_error = b.extinction.quadrature_error + b.extinction.tail_error;
          row.resonance_error = b.extinction.resonance_error;
          row.actual_error = std::abs(b.extinction.value - reference);
          row.evaluations = b.evaluations;
          row.resonances_resolved = b.resonances_resolved;
          rows.push_back(row);
      }
}

}  // namespace

std::vector<QuadratureTradeoffRow> quadrature_tradeoff(double wavelength_m, int repeats) {
  std::vector<QuadratureTradeoffRow> rows;
  const auto m = refractive_index_table("water").at(wavelength_m);
  struct Distribution {
    std::string name;
    SizeDistribution d;
  };
  const std::vector<Distribution> distributions = {
      {"fog:radiation", preset_distribution("radiation")},
      {"log-normal r_g=3um sigma_g=1.03", SizeDistribution::log_normal(1e8, 3e-6, 1.03)},
      {"fog:advection", preset_distribution("advection")}};
  for (const auto& dist : distributions) {
    std::ostringstream name;
    name << dist.name << " @ " << wavelength_m * 1e9 << " nm";
    const TradeoffCase c{name.str(), dist.d, wavelength_m, m, repeats};
    const auto reference = add_reference_row(c, rows);
    if (!reference) continue;
    add_contour_rows(c, reference->extinction.value, rows);
    if (dist.name == "fog:advection") continue;  // real-axis rows take seconds each there
    add_real_axis_rows(c, reference->extinction.value, rows);
  }
  return rows;
}

std::string quadrature_tradeoff_csv(const std::vector<QuadratureTradeoffRow>& rows) {
  std::ostringstream o;
  o << "case,rel_tolerance,kronrod_points,tail_fraction,resonances_resolved,sigma_per_m,"
       "reported_quadrature_tail_error_per_m,resonance_error_per_m,actual_error_per_m,evaluations,milliseconds\n";
  for (const auto& r : rows) {
    o.precision(6);
    o << '"' << r.case_name << "\"," << r.rel_tolerance << "," << r.kronrod_points << "," << r.tail_fraction << ","
      << r.resonances_resolved << ",";
    o.precision(12);
    o << r.sigma_per_m << ",";
    o.precision(6);
    o << r.reported_quadrature_tail_error << "," << r.resonance_error << "," << r.actual_error << ","
      << r.evaluations << "," << r.milliseconds << "\n";
  }
  return o.str();
}

}  // namespace attenuvis::validation
