// Benchmark of the bulk optics of a size distribution (bulk_optics.hpp) on one
// core: for the seed's two fogs (P.1817-1 advection and radiation presets) at
// 550 nm and 1.55 um, water from Hale & Querry (1973), the cost of
//   (a) sigma_ext, sigma_sca, sigma_abs, albedo, g (the default request),
//   (b) the same plus the backscatter coefficient and lidar ratio,
//   (c) (b) plus the Legendre moments chi_0..chi_L (L from the command line),
// with every value and its reported error.  Times are printed as ratios to (a)
// measured in the same run.
// With "table" as first argument instead: sigma_ext of a log-normal (r_g = 5 um,
// sigma_g = 1.5, 100 cm^-3) at 550 nm and 1.55 um, rel. tol. 1e-9, given
// analytically (contour rule, and the real-axis rule) and as a 200-point
// piecewise-linear table of the same density (segmented contour, the route
// sigma() takes for tables, and the real-axis rule), each with its reported
// error and, for the table, its actual error against the segmented contour
// along an independent path at 1e-12 (height 6, slope 0.15, long double);
// then the segmented contour at tolerances 1e-4 ... 1e-10 (error against time).
// With "moments" as first argument: error against run time of the Legendre
// moments chi_0..chi_L (L = 64 by default) of advection fog at 550 nm and
// 1.55 um: the whole optics (passes A and B of mie_bulk_optics), then pass B
// alone (integrate_bulk_optics with the moments, as mie_bulk_optics runs it)
// at quadrature targets from 1e-9 to 1e-4, each with its evaluations, time, the
// largest reported error of any chi_l and the largest change of any chi_l from
// the 1e-9 run (which the reported errors must cover).
// Times are CPU seconds of the process on one thread (TBB limited to one), which
// other users of a shared machine inflate far less than wall time.
// With "bins" as first argument: sigma_ext of the binned raindrop spectra of
// docs/guide/optics-tables.md (0.5-1 mm with 100 m^-3; the same plus 0.1-0.5 mm
// with 1000 m^-3; a bin is a constant density on its interval) at 200 nm,
// 550 nm, 1.55 um and 10.6 um, rel. tol. 1e-9, by the segmented contour on all
// hardware threads: wall and CPU seconds of the call (best of three; without
// the program's start, which `attenuvis sigma` adds), evaluations, value and
// reported error.
// Usage: bulk_optics_speed [L=4] [fog ...] | bulk_optics_speed table | bulk_optics_speed moments [L=64]
//        | bulk_optics_speed bins
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "attenuvis/weather.hpp"

namespace w = attenuvis::weather;

namespace {

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

template <class F>
double seconds(F&& f) {
  const double t0 = cpu_now();
  f();
  return cpu_now() - t0;
}

// The shortest of `runs` timings (the machine is shared; the first call also
// pays for loading tables).
template <class F>
double best_seconds(F&& f, int runs) {
  double best = seconds(f);
  for (int i = 1; i < runs; ++i) best = std::min(best, seconds(f));
  return best;
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

// The table benchmark (see the head of this file).
int table_benchmark() {
  const auto analytic = w::SizeDistribution::log_normal(1e8, 5e-6, 1.5);
  // 200 points log-spaced over the radii holding all but 1e-12 of the r^2 moment.
  const auto sup = analytic.support(2.0, 1e-12);
  const double lo = std::log(sup.breakpoints_m.front()), hi = std::log(sup.breakpoints_m.back());
  std::vector<w::TabulatedSegment> segments;
  const int points = 200;
  for (int i = 0; i + 1 < points; ++i) {
    const double r0 = std::exp(lo + (hi - lo) * i / (points - 1)), r1 = std::exp(lo + (hi - lo) * (i + 1) / (points - 1));
    segments.push_back({r0, r1, analytic.density(r0), analytic.density(r1)});
  }
  const auto table = w::SizeDistribution::tabulated(segments, "200-point log-normal");
  for (double wavelength : {550e-9, 1.55e-6}) {
    const auto m = w::refractive_index_table("water").at(wavelength);
    std::printf("log-normal r_g = 5 um, sigma_g = 1.5, 100 cm^-3, water at %.0f nm, rel. tol 1e-9, one core:\n",
                wavelength * 1e9);
    std::optional<w::ContourExtinction> c, seg, ref;
    const double t_contour = best_seconds([&] { c = w::contour_extinction(analytic, wavelength, m, {}); }, 5);
    std::printf("  analytic, contour rule           sigma = %.12g +- %.2e 1/m, %8zu evaluations, %.4f s\n",
                c->extinction.value, c->extinction.error(), c->evaluations, t_contour);
    w::BulkOptics a, t;
    const double t_axis = seconds([&] { a = w::bulk_optics(analytic, wavelength, m); });
    std::printf("  analytic, real axis              sigma = %.12g +- %.2e 1/m, %8zu evaluations, %.4f s (%.0fx contour)\n",
                a.extinction.value, a.extinction.error(), a.evaluations, t_axis, t_axis / t_contour);
    w::SegmentedContourSettings r;
    r.rel_tolerance = 1e-12;
    r.height = 6;
    r.angle = 0.15;
    r.verify = true;
    r.spans = false;  // one panel per row: not the product integration under test
    r.sqrt_axis_panels = false;  // the axis panels in y: not the 7-point rule in sqrt(y) under test
    r.max_evaluations = 2000000;
    ref = w::segmented_contour_extinction(table, wavelength, m, r);
    const double reference = ref->extinction.value;
    const double t_seg = best_seconds([&] { seg = w::segmented_contour_extinction(table, wavelength, m, {}); }, 5);
    std::printf("  200-point table, segmented       sigma = %.12g +- %.2e 1/m, %8zu evaluations, %.4f s (%.1fx contour), "
                "actual error %.1e\n",
                seg->extinction.value, seg->extinction.error(), seg->evaluations, t_seg, t_seg / t_contour,
                std::abs(seg->extinction.value - reference));
    const double t_table = seconds([&] { t = w::bulk_optics(table, wavelength, m); });
    std::printf("  200-point table, real axis       sigma = %.12g +- %.2e 1/m, %8zu evaluations, %.4f s (%.0fx contour, "
                "%.0fx segmented), actual error %.1e\n",
                t.extinction.value, t.extinction.error(), t.evaluations, t_table, t_table / t_contour, t_table / t_seg,
                std::abs(t.extinction.value - reference));
    std::printf("  reference: segmented contour, height 6, slope 0.15, one panel per row, long double, rel. tol 1e-12: %.14g +- %.1e 1/m\n",
                reference, ref->extinction.error());
    // Error against run time: the table at looser and tighter tolerances.
    for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      w::SegmentedContourSettings st;
      st.rel_tolerance = tol;
      std::optional<w::ContourExtinction> r;
      const double t_r = best_seconds([&] { r = w::segmented_contour_extinction(table, wavelength, m, st); }, 3);
      std::printf("    segmented, rel. tol %.0e: %8zu evaluations, %.4f s, reported error %.1e, actual %.1e 1/m\n", tol,
                  r->evaluations, t_r, r->extinction.error(), std::abs(r->extinction.value - reference));
    }
  }
  return 0;
}

// The moments benchmark (see the head of this file).
int moments_benchmark(int L) {
  const auto d = w::preset_distribution("advection");
  for (double wavelength : {550e-9, 1.55e-6}) {
    const auto m = w::refractive_index_table("water").at(wavelength);
    std::printf("advection fog at %.0f nm, Legendre moments chi_0..chi_%d, one core:\n", wavelength * 1e9, L);
    w::QuadratureSettings s;
    s.backscatter = true;
    s.legendre_moments = L;
    w::BulkOptics all;
    const double t_all = seconds([&] { all = w::bulk_optics(d, wavelength, m, s); });
    double worst = 0;
    for (double e : all.moments_error) worst = std::max(worst, e);
    std::printf("  whole optics (sigma..g, beta_pi, chi_l): %zu evaluations, %.2f s, max chi_l error %.2e\n",
                all.evaluations, t_all, worst);
    std::printf("  pass B alone:   target  evaluations   time [s]  max chi_l error  max |chi_l - chi_l(1e-9)|\n");
    std::vector<double> tightest;
    for (double target : {1e-9, 1e-7, 1e-6, 1e-5, 1e-4}) {
      w::QuadratureSettings b = s;  // as mie_bulk_optics sets up pass B
      b.backscatter = false;
      b.rel_tolerance = target;
      b.angular_tolerance = target;
      w::BulkOptics r;
      const double t = seconds([&] { r = w::integrate_bulk_optics(d, wavelength, w::mie_efficiencies(m, b), b, m); });
      if (tightest.empty()) tightest = r.moments;
      double err = 0, change = 0;
      for (int l = 0; l <= L; ++l) {
        err = std::max(err, r.moments_error[l]);
        change = std::max(change, std::abs(r.moments[l] - tightest[l]));
      }
      std::printf("                 %7.0e  %11zu  %9.2f  %15.2e  %25.2e%s\n", target, r.evaluations, t, err, change,
                  target == std::max(s.rel_tolerance, 1e-6) ? "  (default)" : "");
    }
  }
  return 0;
}

// The bins benchmark (see the head of this file).
int bins_benchmark() {
  struct Bin {
    double lo_mm, hi_mm, count_per_m3;
  };
  const std::vector<std::pair<const char*, std::vector<Bin>>> spectra = {
      {"0.5-1 mm, 100 m^-3", {{0.5, 1.0, 100}}},
      {"+ 0.1-0.5 mm, 1000 m^-3", {{0.1, 0.5, 1000}, {0.5, 1.0, 100}}}};
  std::printf("binned raindrop spectra, sigma_ext by the segmented contour, rel. tol 1e-9, all hardware threads, best "
              "of 3 (wall) and its CPU:\n");
  std::printf("%-26s %8s %18s %10s %11s %9s %9s\n", "spectrum", "lambda", "sigma_ext [1/m]", "error", "evaluations",
              "wall [s]", "cpu [s]");
  for (const auto& [name, bins] : spectra) {
    std::vector<w::TabulatedSegment> segments;
    for (const Bin& b : bins) {
      const double n = b.count_per_m3 / ((b.hi_mm - b.lo_mm) * 1e-3);  // per m^3 per m of radius
      segments.push_back({b.lo_mm * 1e-3, b.hi_mm * 1e-3, n, n});
    }
    const auto d = w::SizeDistribution::tabulated(segments, name);
    for (double wavelength : {200e-9, 550e-9, 1.55e-6, 10.6e-6}) {
      const auto m = w::refractive_index_table("water").at(wavelength);
      std::optional<w::ContourExtinction> r;
      double wall = 1e300, cpu = 0;
      for (int run = 0; run < 3; ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpu_now();
        r = w::segmented_contour_extinction(d, wavelength, m, {});
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (t < wall) wall = t, cpu = cpu_now() - c0;
      }
      if (!r) return std::printf("the segmented contour declined %s\n", name), 1;
      std::printf("%-26s %6.0f nm %18.10e %10.2e %11zu %9.3f %9.3f\n", name, wavelength * 1e9, r->extinction.value,
                  r->extinction.error(), r->evaluations, wall, cpu);
      std::fflush(stdout);
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "bins") return bins_benchmark();
  if (argc > 1 && std::string(argv[1]) == "table") {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    return table_benchmark();
  }
  if (argc > 1 && std::string(argv[1]) == "moments") {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    return moments_benchmark(argc > 2 ? std::atoi(argv[2]) : 64);
  }
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
