// Benchmark of the aerosol integrals (weather/aerosol_optics.hpp), printed as
// ratios to a baseline measured in this run: one Lorenz-Mie evaluation at
// x = 100 (attenuvis::mie::sphere, its default precision).
//   1. What one component costs per wavelength: waso (x << 1 at 10.6 um) and
//      coarse sea salt, dry and at 99 %, at 355 nm, 550 nm and 10.6 um:
//      evaluations, time, and time per evaluation (small x: a short series).
//   2. A humidity table: haze:urban:rh=0..99/9 (12 humidities) over
//      81 wavelengths (400:800:5nm), every table quantity, on 2 threads and
//      on 1, from a cold process (no per-particle optics kept).
//   3. Error against time: urban haze at 0, 50, 95, 99 % RH at 355, 550 and
//      1064 nm, sigma_ext at tolerances 1e-3 .. 1e-9 against a reference at
//      1e-11 (its own reported error printed): the largest actual and
//      reported relative errors and the time of the 12 integrals.
// Usage: aerosol_speed
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "attenuvis/mie.hpp"
#include "attenuvis/weather.hpp"

namespace w = attenuvis::weather;

namespace {

template <class F>
double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One Mie evaluation at x = 100, m = 1.5 + 0.01i, in s (best of three runs of 1000).
double mie_unit_seconds() {
  double best = 1e300;
  for (int r = 0; r < 3; ++r)
    best = std::min(best, seconds([] {
      volatile double q = 0;
      for (int i = 0; i < 1000; ++i) q = q + attenuvis::mie::sphere(100.0 + 1e-3 * i, {1.5, 0.01}).qext;
    }) / 1000);
  return best;
}

void per_component(double unit) {
  std::printf("1. One component, one particle per cm^3, tolerance 1e-9 (sigma_ext, sca, abs, g):\n");
  for (w::AerosolComponent c : {w::AerosolComponent::waso, w::AerosolComponent::sscm})
    for (double rh : {0.0, 99.0})
      for (double nm : {355.0, 550.0, 10600.0}) {
        const w::AerosolPopulation p = w::component_populations(c, rh, w::HumidityRule::kappa).front();
        w::BulkOptics b;
        const double t = seconds([&] {
          b = w::mie_bulk_optics(w::population_distribution(p, 1.0), nm * 1e-9, p.index_at(nm * 1e-9), {});
        });
        std::printf("   %-5s %3.0f %% at %6.0f nm: x <= %7.1f, %7zu evaluations, %8.4f s = %9.0f units, "
                    "%6.2f units per evaluation\n",
                    w::to_string(c).c_str(), rh, nm, b.max_size_parameter, b.evaluations, t, t / unit,
                    t / unit / static_cast<double>(b.evaluations));
      }
}

void urban_table(double unit) {
  const auto conditions = w::expand_conditions("haze:urban:rh=0..99/9");
  const auto wavelengths = w::parse_wavelength_list("400:800:5nm");
  std::vector<w::Quantity> all;
  for (const auto& q : w::table_quantities()) all.push_back(q.id);
  std::printf("2. table --conditions haze:urban:rh=0..99/9 (%zu) --wavelengths 400:800:5nm (%zu), %zu quantities:\n",
              conditions.size(), wavelengths.size(), all.size());
  for (int threads : {2, 1}) {
    // A new humidity grid each time: the per-particle optics of the first run are not reused.
    const auto shifted = w::expand_conditions(threads == 2 ? "haze:urban:rh=0..99/9" : "haze:urban:rh=0.5..98.5/9");
    w::SigmaTable t;
    const double s = seconds([&] { t = w::sigma_table(shifted, wavelengths, w::Settings{}, threads, all); });
    double worst = 0;
    for (const auto& cell : t.cells) worst = std::max(worst, cell.sigma.error_per_m / cell.sigma.per_m);
    std::printf("   %d thread(s): %.2f s = %.0f units for %zu cells; largest reported relative error of sigma_ext "
                "%.1e\n",
                threads, s, s / unit, t.cells.size(), worst);
  }
}

void error_against_time(double unit) {
  std::printf("3. Error against time, urban haze at 0, 50, 95, 99 %% x 355, 550, 1064 nm (12 integrals):\n"
              "   tolerance   largest actual error   largest reported error   time [s]   units\n");
  std::vector<w::AerosolCondition> cases;
  for (double rh : {0.0, 50.0, 95.0, 99.0})
    cases.push_back({w::AerosolMixture::urban, w::info(w::AerosolMixture::urban).amounts, rh, w::HumidityRule::kappa,
                     w::AsGiven{}});
  const double wavelengths[] = {355e-9, 550e-9, 1064e-9};
  w::Settings reference_settings;
  reference_settings.rel_tolerance = 1e-11;
  std::vector<w::Sigma> reference;
  for (const auto& c : cases)
    for (double wl : wavelengths) reference.push_back(w::aerosol_sigma(c, wl, reference_settings));
  double ref_error = 0;
  for (const auto& r : reference) ref_error = std::max(ref_error, r.error_per_m / r.per_m);
  for (double tol : {1e-3, 1e-4, 1e-6, 1e-9}) {
    w::Settings s;
    s.rel_tolerance = tol;
    double actual = 0, reported = 0;
    std::size_t i = 0;
    const double t = seconds([&] {
      for (const auto& c : cases)
        for (double wl : wavelengths) {
          const w::Sigma r = w::aerosol_sigma(c, wl, s);
          actual = std::max(actual, std::abs(r.per_m - reference[i].per_m) / reference[i].per_m);
          reported = std::max(reported, r.error_per_m / r.per_m);
          ++i;
        }
    });
    std::printf("   %8.0e   %20.2e   %22.2e   %8.3f   %6.0f\n", tol, actual, reported, t, t / unit);
  }
  std::printf("   (reference: tolerance 1e-11, its largest reported relative error %.1e)\n", ref_error);
}

}  // namespace

int main() {
  const double unit = mie_unit_seconds();
  std::printf("aerosol_speed: baseline unit = one Mie evaluation at x = 100: %.3g s\n", unit);
  per_component(unit);
  urban_table(unit);
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    error_against_time(unit);
  }
  return 0;
}
