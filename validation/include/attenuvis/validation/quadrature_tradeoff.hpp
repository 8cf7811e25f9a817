// Error against run time for the weather module's quadrature settings
// (tolerance, Gauss-Kronrod order, tail cut), for the reproduction report and
// the benchmark.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::validation {

// One run of the quadrature trade-off: a tolerance, its cost and its error.
struct QuadratureTradeoffRow {
  std::string case_name;      // e.g. "fog:advection @ 550 nm"
  double rel_tolerance = 0;
  int kronrod_points = 0;
  double tail_fraction = 0;
  std::size_t resonances_resolved = 0;  // real axis: resonances given a product-rule panel (bulk_optics.hpp)
  double sigma_per_m = 0;
  double reported_quadrature_tail_error = 0;  // what the integrator claims (quadrature + tails)
  double actual_error = 0;    // |sigma - reference|; reference: contour integral, tol 1e-12, tail 1e-16
  double resonance_error = 0; // the bound on the resonances left unresolved
  std::size_t evaluations = 0;
  double milliseconds = 0;    // wall time of one call, best of `repeats`
};

// Moderate radiation fog, a narrow log-normal (r_g = 3 um, sigma_g = 1.03) and
// heavy advection fog at `wavelength_m` (Hale & Querry water): the contour rule
// (contour_extinction.hpp, what sigma() uses) at heights 2, 4, 6 and tolerances
// 1e-6, 1e-9, 1e-12, and -- except for advection fog, where each row takes
// seconds -- the real-axis rule (bulk_optics.hpp) over tolerances x Gauss-
// Kronrod orders x tail cuts.  The reference is the
// contour integral at tolerance 1e-12 and tail 1e-16 (its error is in its row).
std::vector<QuadratureTradeoffRow> quadrature_tradeoff(double wavelength_m = 550e-9, int repeats = 3);
std::string quadrature_tradeoff_csv(const std::vector<QuadratureTradeoffRow>& rows);

}  // namespace attenuvis::validation
