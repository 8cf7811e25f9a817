// Benchmark of attenuvis::weather: sigma of advection fog at 550 nm (one core),
// an 81-wavelength x 4-condition table (2 threads), and the quadrature
// error-vs-time table.  Speeds are printed as ratios to a baseline measured in
// this run: one Lorenz-Mie evaluation at x = 100 (attenuvis::mie::sphere).
// Usage: weather_speed [tradeoff.csv]   (writes the trade-off table there)
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "attenuvis/mie.hpp"
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

int main(int argc, char** argv) {
  std::complex<double> m = w::refractive_index_table("water").at(550e-9);
  double mie_s = best_seconds([&] {
    volatile double s = 0;
    for (int i = 0; i < 1000; ++i) s = s + attenuvis::mie::sphere(100.0 + 1e-3 * i, m).qext;
  }, 3) / 1000;
  std::printf("baseline: one Mie evaluation at x = 100: %.2f us\n", mie_s * 1e6);

  for (double tol : {1e-6, 1e-9}) {
    w::QuadratureSettings s;
    s.rel_tolerance = tol;
    w::BulkOptics b;
    double t = best_seconds([&] { b = w::bulk_optics(w::preset_distribution("advection"), 550e-9, m, s); }, 1);
    std::printf("advection fog 550 nm, tol %g: sigma = %.10f +- %.2e 1/m (quadrature %.1e, tails %.1e, resonance %.1e), "
                "%zu evaluations, %.3f s = %.0f Mie-baseline units (target 10 ms)\n",
                tol, b.extinction.value, b.extinction.error(), b.extinction.quadrature_error, b.extinction.tail_error,
                b.extinction.resonance_error, b.evaluations, t, t / mie_s);
  }

  {
    std::vector<w::Condition> conds;
    for (const char* c : {"clear", "rain:8", "snow:dry:4", "fog:radiation"}) conds.push_back(w::parse_condition(c));
    auto wl = w::parse_wavelength_list("380:780:5nm");
    w::Settings s;
    s.rel_tolerance = 1e-6;
    double t = best_seconds([&] { w::sigma_table(conds, wl, s, 2); }, 1);
    std::printf("table %zu wavelengths x %zu conditions (clear, rain:8, snow:dry:4, fog:radiation; tol 1e-6), "
                "2 threads: %.3f s = %.0f Mie-baseline units (target 2 s)\n",
                wl.size(), conds.size(), t, t / mie_s);
  }

  auto rows = w::quadrature_tradeoff(550e-9, 1);
  std::string csv = w::quadrature_tradeoff_csv(rows);
  if (argc > 1) {
    w::write_file_atomically(argv[1], csv);
    std::printf("trade-off table written to %s\n", argv[1]);
  } else {
    std::cout << csv;
  }
  return 0;
}
