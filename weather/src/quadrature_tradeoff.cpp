// Error vs. run time of the bulk-optics quadrature settings.
#include "attenuvis/weather/quadrature_tradeoff.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/refractive_index.hpp"

namespace attenuvis::weather {

std::vector<QuadratureTradeoffRow> quadrature_tradeoff(double wavelength_m, int repeats) {
  std::vector<QuadratureTradeoffRow> rows;
  auto m = refractive_index_table("water").at(wavelength_m);
  for (const char* preset : {"advection", "radiation"}) {
    auto d = preset_distribution(preset);
    QuadratureSettings ref;
    ref.rel_tolerance = 1e-13;
    ref.kronrod_points = 61;
    ref.tail_fraction = 1e-16;
    ref.max_evaluations = 4000000;
    double reference = bulk_optics(d, wavelength_m, m, ref).extinction.value;
    std::ostringstream name;
    name << "fog:" << preset << " @ " << wavelength_m * 1e9 << " nm";
    for (double tol : {1e-4, 1e-6, 1e-9, 1e-11})
      for (int order : {15, 31, 61})
        for (double tail : {0.0, 1e-6}) {
          QuadratureSettings s;
          s.rel_tolerance = tol;
          s.kronrod_points = order;
          s.tail_fraction = tail;
          QuadratureTradeoffRow row;
          row.case_name = name.str();
          row.rel_tolerance = tol;
          row.kronrod_points = order;
          row.tail_fraction = tail > 0 ? tail : 1e-3 * tol;
          double best = std::numeric_limits<double>::infinity();
          BulkOptics b;
          for (int r = 0; r < std::max(1, repeats); ++r) {
            auto t0 = std::chrono::steady_clock::now();
            b = bulk_optics(d, wavelength_m, m, s);
            auto t1 = std::chrono::steady_clock::now();
            best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
          }
          row.sigma_per_m = b.extinction.value;
          row.reported_quadrature_tail_error = b.extinction.quadrature_error + b.extinction.tail_error;
          row.resonance_error = b.extinction.resonance_error;
          row.actual_error = std::abs(b.extinction.value - reference);
          row.evaluations = b.evaluations;
          row.milliseconds = best;
          rows.push_back(row);
        }
  }
  return rows;
}

std::string quadrature_tradeoff_csv(const std::vector<QuadratureTradeoffRow>& rows) {
  std::ostringstream o;
  o.precision(6);
  o << "case,rel_tolerance,kronrod_points,tail_fraction,sigma_per_m,reported_quadrature_tail_error_per_m,"
       "actual_error_per_m,resonance_error_per_m,evaluations,milliseconds\n";
  for (const auto& r : rows) {
    o << '"' << r.case_name << "\"," << r.rel_tolerance << "," << r.kronrod_points << "," << r.tail_fraction << ",";
    o.precision(12);
    o << r.sigma_per_m << ",";
    o.precision(6);
    o << r.reported_quadrature_tail_error << "," << r.actual_error << "," << r.resonance_error << "," << r.evaluations
      << "," << r.milliseconds << "\n";
  }
  return o.str();
}

}  // namespace attenuvis::weather
