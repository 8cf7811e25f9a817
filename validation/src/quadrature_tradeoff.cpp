// Error vs. run time of the bulk-optics quadrature settings.
#include "attenuvis/validation/quadrature_tradeoff.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/contour_extinction.hpp"
#include "attenuvis/weather/refractive_index.hpp"

namespace attenuvis::validation {

using namespace attenuvis::weather;

std::vector<QuadratureTradeoffRow> quadrature_tradeoff(double wavelength_m, int repeats) {
  std::vector<QuadratureTradeoffRow> rows;
  auto m = refractive_index_table("water").at(wavelength_m);
  struct Case { std::string name; SizeDistribution d; };
  std::vector<Case> cases = {{"fog:radiation", preset_distribution("radiation")},
                             {"log-normal r_g=3um sigma_g=1.03", SizeDistribution::log_normal(1e8, 3e-6, 1.03)},
                             {"fog:advection", preset_distribution("advection")}};
  const auto timed = [&](auto&& f) {
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < std::max(1, repeats); ++r) {
      auto t0 = std::chrono::steady_clock::now();
      f();
      auto t1 = std::chrono::steady_clock::now();
      best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    return best;
  };
  for (const auto& c : cases) {
    std::ostringstream name;
    name << c.name << " @ " << wavelength_m * 1e9 << " nm";
    // Reference: the contour integral (contour_extinction.hpp), which resolves
    // the resonances, at tolerance 1e-12 and tail 1e-16; its own error bound
    // is in its row.
    ContourSettings ref;
    ref.rel_tolerance = 1e-12;
    ref.tail_fraction = 1e-16;
    ref.max_evaluations = 4000000;
    ref.verify = true;
    const auto reference = contour_extinction(c.d, wavelength_m, m, ref);
    if (!reference) continue;
    QuadratureTradeoffRow ref_row;
    ref_row.case_name = name.str() + " (reference: contour h=4, tol 1e-12, verified by halving)";
    ref_row.rel_tolerance = ref.rel_tolerance;
    ref_row.kronrod_points = ref.kronrod_points;
    ref_row.tail_fraction = ref.tail_fraction;
    ref_row.sigma_per_m = reference->extinction.value;
    ref_row.reported_quadrature_tail_error = reference->extinction.error();
    ref_row.evaluations = reference->evaluations;
    rows.push_back(ref_row);
    // The contour rule (what sigma() uses) at its settings.
    for (double height : {2.0, 4.0, 6.0})
      for (double tol : {1e-6, 1e-9, 1e-12}) {
        ContourSettings s;
        s.rel_tolerance = tol;
        s.height = height;
        std::optional<ContourExtinction> r;
        QuadratureTradeoffRow row;
        row.milliseconds = timed([&] { r = contour_extinction(c.d, wavelength_m, m, s); });
        std::ostringstream label;
        label << name.str() << " contour h=" << height;
        row.case_name = label.str();
        row.rel_tolerance = tol;
        row.kronrod_points = s.kronrod_points;
        row.tail_fraction = s.effective_tail_fraction();
        row.sigma_per_m = r->extinction.value;
        row.reported_quadrature_tail_error = r->extinction.error();
        row.actual_error = std::abs(r->extinction.value - reference->extinction.value);
        row.evaluations = r->evaluations;
        rows.push_back(row);
      }
    if (c.name == "fog:advection") continue;  // real-axis rows take seconds each there
    auto q = mie_efficiency_batch(m);  // what the bulk integrals use (sigma.cpp)
    for (double resonance_tol : {1e-4, 5e-5, 1e-5})
      for (double tol : {1e-6, 1e-9})
        for (int order : {15, 31})
          for (double tail : {0.0, 1e-6}) {
            QuadratureSettings s;
            s.rel_tolerance = tol;
            s.kronrod_points = order;
            s.tail_fraction = tail;
            s.resonance_tolerance = resonance_tol;
            s.max_evaluations = 2000000;
            QuadratureTradeoffRow row;
            row.case_name = name.str() + " real axis";
            row.rel_tolerance = tol;
            row.kronrod_points = order;
            row.tail_fraction = tail > 0 ? tail : 1e-3 * tol;
            row.resonance_x_span = s.resonance_x_span;
            row.resonance_tolerance = resonance_tol;
            BulkOptics b;
            row.milliseconds = timed([&] { b = integrate_bulk_optics(c.d, wavelength_m, q, s, m); });
            row.sigma_per_m = b.extinction.value;
            row.reported_quadrature_tail_error = b.extinction.quadrature_error + b.extinction.tail_error;
            row.resonance_error = b.extinction.resonance_error;
            row.actual_error = std::abs(b.extinction.value - reference->extinction.value);
            row.evaluations = b.evaluations;
            rows.push_back(row);
          }
  }
  return rows;
}

std::string quadrature_tradeoff_csv(const std::vector<QuadratureTradeoffRow>& rows) {
  std::ostringstream o;
  o << "case,rel_tolerance,kronrod_points,tail_fraction,resonance_x_span,resonance_tolerance,sigma_per_m,"
       "reported_quadrature_tail_error_per_m,resonance_error_per_m,actual_error_per_m,evaluations,milliseconds\n";
  for (const auto& r : rows) {
    o.precision(6);
    o << '"' << r.case_name << "\"," << r.rel_tolerance << "," << r.kronrod_points << "," << r.tail_fraction << ","
      << r.resonance_x_span << "," << r.resonance_tolerance << ",";
    o.precision(12);
    o << r.sigma_per_m << ",";
    o.precision(6);
    o << r.reported_quadrature_tail_error << "," << r.resonance_error << "," << r.actual_error << ","
      << r.evaluations << "," << r.milliseconds << "\n";
  }
  return o.str();
}

}  // namespace attenuvis::validation
