// Benchmark of attenuvis::weather: sigma of heavy advection fog at 550 nm on
// one core (default settings and tolerances 1e-6 / 1e-9), the cost floor of
// sampling Q_ext's ripple, an 81-wavelength x 4-condition table on 2 threads,
// and the quadrature error-vs-time table.  Speeds are printed as ratios to a
// baseline measured in this run: one Lorenz-Mie evaluation at x = 100
// (attenuvis::mie::sphere, its default precision).
// Usage: weather_speed [tradeoff.csv]   (writes the trade-off table there)
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include <boost/math/constants/constants.hpp>

#include <tbb/global_control.h>

#include "attenuvis/io/staged_file.hpp"
#include "attenuvis/mie.hpp"
#include "attenuvis/validation/quadrature_tradeoff.hpp"
#include "attenuvis/weather.hpp"

namespace w = attenuvis::weather;

template <class F>
double best_seconds(F&& f, int repeats) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

void print_fog(const char* label, const w::BulkOptics& b, double seconds, double mie_s) {
  const auto& e = b.extinction;
  std::printf("  %-34s sigma = %.9f +- %.2e 1/m (%.1e relative; quadrature %.1e, tails %.1e, resonance %.1e), "
              "%zu Mie evaluations, x <= %.0f, %.3f s = %.0f baseline units (target 10 ms = %.0f units)\n",
              label, e.value, e.error(), e.error() / e.value, e.quadrature_error, e.tail_error, e.resonance_error,
              b.evaluations, b.max_size_parameter, seconds, seconds / mie_s, 0.010 / mie_s);
}

// The unit every time is printed in: one Mie evaluation at x = 100, in s.
double mie_unit_seconds(std::complex<double> m) {
  return best_seconds([&] {
    volatile double s = 0;
    for (int i = 0; i < 1000; ++i) s = s + attenuvis::mie::sphere(100.0 + 1e-3 * i, m).qext;
  }, 3) / 1000;
}

const w::MieCondition kAdvection{w::FogPreset::advection, w::SettingsWaterTable{}, w::AsGiven{}};

// The real-axis rule (bulk_optics: resonances located, resolved or bounded)
// at three tolerances.
void real_axis_runs(std::complex<double> m, double mie_s) {
  struct Run { const char* label; double tol; };
  for (const Run& r : {Run{"real axis tol 1e-4", 1e-4}, Run{"real axis tol 1e-6", 1e-6},
                       Run{"real axis tol 1e-9", 1e-9}}) {
    w::QuadratureSettings q;
    q.rel_tolerance = r.tol;
    w::BulkOptics b;
    auto d = w::condition_distribution(kAdvection);
    double t = best_seconds([&] { b = w::integrate_bulk_optics(d, 550e-9, w::mie_efficiency_batch(m), q, m); }, 1);
    print_fog(r.label, b, t, mie_s);
  }
}

// What sigma() (the CLI, tables, reproduce) computes: the contour integral
// above the real axis (contour_extinction.hpp), against its own value at
// tolerance 1e-12, tail 1e-16.
void contour_runs(std::complex<double> m, double mie_s) {
  auto d = w::condition_distribution(kAdvection);
  w::ContourSettings ref_settings;
  ref_settings.rel_tolerance = 1e-12;
  ref_settings.tail_fraction = 1e-16;
  const double ref = w::contour_extinction(d, 550e-9, m, ref_settings)->extinction.value;
  for (double h : {4.0, 2.0, 6.0})
    for (double tol : {1e-9, 1e-6, 1e-12}) {
      w::ContourSettings cs;
      cs.height = h;
      cs.rel_tolerance = tol;
      std::optional<w::ContourExtinction> r;
      double t = best_seconds([&] { r = w::contour_extinction(d, 550e-9, m, cs); }, 3);
      const auto& e = r->extinction;
      std::printf("  contour h=%-3g tol %-7.0e %s sigma = %.12f +- %.2e 1/m (%.1e relative), actual error %.1e "
                  "relative, %zu Mie evaluations, %.4f s = %.0f baseline units (target 10 ms = %.0f units)\n",
                  h, tol, h == 4.0 && tol == 1e-9 ? "(default)" : "         ", e.value, e.error(),
                  e.error() / e.value, std::abs(e.value - ref) / ref, r->evaluations, t, t / mie_s, 0.010 / mie_s);
    }
}

// Cost floor of any rule that samples Q_ext's ripple (period ~0.8 in x for
// water): Mie at 4 nodes per period (spacing 0.2) over the x range the
// default tail cut keeps, without any resonance resolved.
void cost_floor(std::complex<double> m, double mie_s) {
  auto sup = w::condition_distribution(kAdvection).support(2.0, 1e-12);
  double k = 2 * boost::math::constants::pi<double>() / 550e-9;
  double xa = k * sup.breakpoints_m.front(), xb = k * sup.breakpoints_m.back();
  auto q = w::mie_efficiencies(m);
  std::size_t n = 0;
  double t = best_seconds([&] {
    volatile double s = 0;
    n = 0;
    for (double x = xa; x <= xb; x += 0.2, ++n) s = s + q(x).qext;
  }, 1);
  double t1000 = best_seconds([&] {
    volatile double s = 0;
    for (int i = 0; i < 200; ++i) s = s + q(1000.0 + 1e-3 * i).qext;
  }, 1) / 200;
  std::printf("  cost floor: %zu Mie evaluations at spacing 0.2 over %.1f < x < %.0f (tail cut 1e-12): %.3f s "
              "= %.0f baseline units; Mie at x = 1000 costs %.3f us per unit of x\n",
              n, xa, xb, t, t / mie_s, t1000 * 1e6 / 1000);
}

// The 81-wavelength x 4-condition table on 2 threads, at two tolerances, and
// every table quantity against sigma_ext alone.
void table_runs(double mie_s) {
  std::vector<w::LabelledCondition> conds;
  for (const char* c : {"clear", "rain:8", "snow:dry:4", "fog:radiation"}) conds.push_back({c, w::parse_condition(c)});
  auto wl = w::parse_wavelength_list("380:780:5nm");
  // sigma() caches Mie results per process: each tolerance is a fresh set of keys.
  for (double tol : {1e-9, 1e-6}) {
    w::Settings s;
    s.rel_tolerance = tol;
    double t = best_seconds([&] { w::sigma_table(conds, wl, s, 2); }, 1);
    std::printf("table %zu wavelengths x %zu conditions (clear, rain:8, snow:dry:4, fog:radiation; tol %.0e), "
                "2 threads: %.3f s = %.0f baseline units (target 2 s)\n",
                wl.size(), conds.size(), tol, t, t / mie_s);
  }
  // Every table quantity (sigma_ext, sigma_sca, sigma_abs, ssa, g with errors) against sigma_ext alone,
  // both in this run at a tolerance not used above (fresh cache keys): the cost of the real-axis optics.
  w::Settings s;
  s.rel_tolerance = 1e-8;
  const auto all = w::parse_quantity_list("sigma_ext,sigma_sca,sigma_abs,ssa,g");
  const double t_ext = best_seconds([&] { w::sigma_table(conds, wl, s, 2); }, 1);
  const double t_all = best_seconds([&] { w::sigma_table(conds, wl, s, 2, all); }, 1);
  std::printf("table %zu wavelengths x %zu conditions (tol 1e-8), 2 threads: sigma_ext %.3f s, all five "
              "quantities %.3f s = %.0fx sigma_ext alone\n",
              wl.size(), conds.size(), t_ext, t_all, t_all / t_ext);
}

int main(int argc, char** argv) {
  std::complex<double> m = w::refractive_index_table("water").at(550e-9);
  const double mie_s = mie_unit_seconds(m);
  std::printf("baseline: one Mie evaluation at x = 100: %.2f us\n", mie_s * 1e6);
  {
    // One core: the single-sigma figure must not borrow the second core.
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    std::printf("heavy advection fog at 550 nm, one core (Hale & Querry m = %.4f+%.3gi); real-axis rule "
                "(bulk_optics, resonances as an error term) first, then the contour rule sigma() uses:\n",
                m.real(), m.imag());
    real_axis_runs(m, mie_s);
    contour_runs(m, mie_s);
    cost_floor(m, mie_s);
  }
  table_runs(mie_s);

  auto rows = attenuvis::validation::quadrature_tradeoff(550e-9, 1);
  std::string csv = attenuvis::validation::quadrature_tradeoff_csv(rows);
  if (argc > 1) {
    attenuvis::io::write_file_atomically(argv[1], csv);
    std::printf("trade-off table written to %s\n", argv[1]);
  } else {
    std::cout << csv;
  }
  return 0;
}
