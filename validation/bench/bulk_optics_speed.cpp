// Benchmark of the bulk optics of a size distribution (bulk_optics.hpp) on one
// core: for the seed's two fogs (P.1817-1 advection and radiation presets) at
// 550 nm and 1.55 um, water from Hale & Querry (1973), the cost of
//   (a) sigma_ext, sigma_sca, sigma_abs, albedo, g (the default request),
//   (b) the same plus the backscatter coefficient and lidar ratio,
//   (c) (b) plus the Legendre moments chi_0..chi_L (L from the command line),
// with every value and its reported error.  Times are printed as ratios to (a)
// measured in the same run.
// Usage: bulk_optics_speed [L=4] [fog ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "attenuvis/weather.hpp"

namespace w = attenuvis::weather;

namespace {

template <class F>
double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void print(const char* label, const w::BulkOptics& b, double t, double t_base) {
  std::printf("    %-28s %8zu evaluations, %8.3f s (%.1fx of sigma_ext alone)\n", label, b.evaluations, t, t / t_base);
}

void print_values(const w::BulkOptics& b) {
  auto row = [](const char* name, const w::IntegralEstimate& e, const char* unit) {
    std::printf("      %-12s %.10g +- %.2e %s (%.1e relative; resonance %.1e)\n", name, e.value, e.error(), unit,
                e.error() / e.value, e.resonance_error);
  };
  row("sigma_ext", b.extinction, "1/m");
  row("sigma_sca", b.scattering, "1/m");
  row("sigma_abs", b.absorption, "1/m");
  std::printf("      %-12s %.10g +- %.2e\n", "albedo", b.albedo, b.albedo_error);
  std::printf("      %-12s %.10g +- %.2e\n", "g", b.asymmetry, b.asymmetry_error);
  if (b.backscatter_computed) {
    row("beta_pi", b.backscatter, "1/(m sr)");
    std::printf("      %-12s %.8g +- %.2e sr\n", "lidar ratio", b.lidar_ratio, b.lidar_ratio_error);
  }
  for (std::size_t l = 1; l < b.moments.size(); ++l)
    std::printf("      chi_%-8zu %.10g +- %.2e\n", l, b.moments[l], b.moments_error[l]);
}

}  // namespace

int main(int argc, char** argv) {
  const int L = argc > 1 ? std::atoi(argv[1]) : 4;
  std::vector<std::string> fogs;
  for (int i = 2; i < argc; ++i) fogs.emplace_back(argv[i]);
  if (fogs.empty()) fogs = {"advection", "radiation"};
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  for (const std::string& fog : fogs)
    for (double wavelength : {550e-9, 1.55e-6}) {
      const auto d = w::preset_distribution(fog);
      const auto m = w::refractive_index_table("water").at(wavelength);
      std::printf("%s fog at %.0f nm (m = %.4f + %.3gi), one core:\n", fog.c_str(), wavelength * 1e9, m.real(),
                  m.imag());
      w::QuadratureSettings s;
      w::BulkOptics base, back, all;
      const double t_base = seconds([&] { base = w::bulk_optics(d, wavelength, m, s); });
      print("sigma_ext, sca, abs, g", base, t_base, t_base);
      s.backscatter = true;
      const double t_back = seconds([&] { back = w::bulk_optics(d, wavelength, m, s); });
      print("+ backscatter", back, t_back, t_base);
      s.legendre_moments = L;
      const double t_all = seconds([&] { all = w::bulk_optics(d, wavelength, m, s); });
      const std::string label = "+ moments to L = " + std::to_string(L);
      print(label.c_str(), all, t_all, t_base);
      print_values(all);
    }
  return 0;
}
