// The current Mie core against Wiscombe's MIEV0 (see
// attenuvis/validation/mie_miev0.hpp).
#include "attenuvis/validation/mie_miev0.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"
#include "block_timing.hpp"
#include "core_batch.hpp"

namespace attenuvis::validation {
namespace {

namespace mie = attenuvis::mie;
using timing::block_ns;

// MIEV0's argument list as gfortran passes it (every argument by reference;
// LOGICAL and INTEGER 4 bytes, REAL 8 and COMPLEX 16 with -fdefault-real-8).
using Cd = std::complex<double>;
using Miev0Entry = void (*)(double* xx, Cd* crefin, int* perfct, double* mimcut, int* anyang, int* numang,
                            double* xmu, int* nmom, int* ipolzn, int* momdim, int* prnt, double* qext, double* qsca,
                            double* gqsc, double* pmom, Cd* sforw, Cd* sback, Cd* s1, Cd* s2, Cd* tforw, Cd* tback,
                            double* spike);

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// MIEV0 is tested up to x = 2e4 and its arrays hold 20,100 terms: beyond,
// it stops the program (ERRMSG, fatal), so larger x are not timed.
constexpr double kMiev0MaxX = 2e4;

}  // namespace

Miev0Library::Miev0Library(const std::string& library_path)
    : library_(library_path, "the MIEV0 library", "miev0_", "validation/bench/miev0/build_miev0.sh") {}

MieQuantities Miev0Library::sphere(double x, std::complex<double> m) const {
  // MIMCUT = 0: every index with Im m > 0 takes MIEV0's absorbing branch.
  // The arrays are sized for MIEV0's self-test on its first call (one angle,
  // one moment), which temporarily replaces the arguments.
  int perfct = 0, anyang = 0, numang = 0, nmom = 0, ipolzn = 0, momdim = 1, prnt[2] = {0, 0};
  double mimcut = 0, xmu[1] = {0}, pmom[2 * 4] = {}, qext = kNaN, qsca = kNaN, gqsc = kNaN, spike = 0;
  Cd crefin = m, sforw, sback, s1[1], s2[1], tforw[2], tback[2];
  const auto miev0 = reinterpret_cast<Miev0Entry>(library_.entry());
  miev0(&x, &crefin, &perfct, &mimcut, &anyang, &numang, xmu, &nmom, &ipolzn, &momdim, prnt, &qext, &qsca, &gqsc, pmom,
        &sforw, &sback, s1, s2, tforw, tback, &spike);
  // SBACK = S(π) = ½ Σ (2n+1)(−1)^(n+1) (aₙ − bₙ): Qback = 4|S(π)|²/x².
  return {qext, qsca, qext - qsca, qsca > 0 ? gqsc / qsca : 0.0, 4 * std::norm(sback) / (x * x)};
}

std::vector<Miev0Cell> mie_speed_vs_miev0(const Miev0Library& miev0, const SpeedOptions& options) {
  mie::Options wiscombe;
  wiscombe.terms = mie::TermRule::wiscombe;
  std::vector<Miev0Cell> cells;
  for (double x : options.xs) {
    if (x > kMiev0MaxX) continue;
    for (const auto& m : options.ms) {
      Miev0Cell c;
      c.x = x;
      c.m = m;
      const auto ns = timing::alternating_min_ns(
          options.min_block_seconds, options.blocks, [&] { return miev0.sphere(x, m).qext; },
          [&] { return mie::sphere(x, m).qext; }, [&] { return mie::sphere(x, m, wiscombe).qext; });
      c.ns_miev0 = ns[0], c.ns_default = ns[1], c.ns_wiscombe = ns[2];
      const auto d = mie::sphere(x, m), w = mie::sphere(x, m, wiscombe);
      c.terms_default = static_cast<int>(d.terms);
      c.terms_wiscombe = static_cast<int>(w.terms);
      if (x <= options.max_referee_x) {
        const MieQuantities ref = mie_referee_quantities(x, m);
        c.err_miev0 = mie_max_relative_error(miev0.sphere(x, m), ref);
        c.err_default = mie_max_relative_error(mie_quantities(d), ref);
        c.err_wiscombe = mie_max_relative_error(mie_quantities(w), ref);
      }
      cells.push_back(c);
    }
  }
  return cells;
}

std::string format_speed_vs_miev0(const std::vector<Miev0Cell>& cells) {
  std::ostringstream os;
  char buf[256];
  os << "time per call against MIEV0 (same run, alternating blocks, thread CPU time, minimum over blocks);\n"
        "ratio = attenuvis time / MIEV0 time (below 1: attenuvis faster); err = max relative error against the "
        "50-digit referee; x <= 2e4 (MIEV0's tested range)\n";
  std::snprintf(buf, sizeof buf, "%-12s %7s | %10s %10s %10s | %7s %7s | %8s %8s %8s | %5s %5s\n", "m", "x",
                "MIEV0 ns", "default", "wiscombe", "ratio", "r wisc", "err MV0", "err def", "err wis", "terms",
                "wisc");
  os << buf;
  for (const auto& c : cells) {
    std::snprintf(buf, sizeof buf, "%-12s %7.0e | %10.4g %10.4g %10.4g | %7.2f %7.2f | %8s %8s %8s | %5d %5d\n",
                  io::index_text(c.m).c_str(), c.x, c.ns_miev0, c.ns_default, c.ns_wiscombe, c.ratio(),
                  c.ns_wiscombe / c.ns_miev0, measured_error_text(c.err_miev0).c_str(),
                  measured_error_text(c.err_default).c_str(), measured_error_text(c.err_wiscombe).c_str(),
                  c.terms_default, c.terms_wiscombe);
    os << buf;
  }
  return os.str();
}

Miev0Batch mie_batch_vs_miev0(const Miev0Library& miev0, Miev0Batch b, int blocks) {
  const std::vector<double> x = batch_size_parameters(b.x_min, b.x_max, b.count);
  b.threads = batch_threads(b.threads);
  CoreBatch core(x, b.m, b.threads);
  auto run_miev0 = [&] {
    double acc = 0;
    for (double xi : x) acc += miev0.sphere(xi, b.m).qext;
    return acc;
  };
  auto run_single = [&] {
    double acc = 0;
    for (double xi : x) acc += mie::sphere(xi, b.m).qext;
    return acc;
  };
  auto run_batch = [&] { return core.one_thread(); };
  auto run_threads = [&] { return core.all_threads(); };
  const double n = static_cast<double>(b.count);
  b.ns_miev0 = b.ns_single = b.ns_batch = b.ns_batch_threads = std::numeric_limits<double>::infinity();
  for (int k = 0; k < std::max(1, blocks); ++k) {
    b.ns_miev0 = std::min(b.ns_miev0, block_ns(run_miev0, 1) / n);
    b.ns_single = std::min(b.ns_single, block_ns(run_single, 1) / n);
    b.ns_batch = std::min(b.ns_batch, block_ns(run_batch, 1) / n);
    b.ns_batch_threads = std::min(b.ns_batch_threads, timing::wall_block_ns(run_threads, 1) / n);
  }
  return b;
}

std::string format_batch_vs_miev0(const Miev0Batch& b) {
  std::ostringstream os;
  char buf[200];
  os << "many spheres against MIEV0: " << b.count << " x uniform in [" << b.x_min << ", " << b.x_max
     << "], m = " << io::index_text(b.m) << " (ns per sphere, minimum over blocks; throughput relative to MIEV0's)\n";
  std::snprintf(buf, sizeof buf, "  MIEV0 loop                  %9.1f\n", b.ns_miev0);
  os << buf;
  std::snprintf(buf, sizeof buf, "  sphere() loop               %9.1f  (%.2fx MIEV0)\n", b.ns_single,
                b.ns_miev0 / b.ns_single);
  os << buf;
  std::snprintf(buf, sizeof buf, "  spheres(), 1 thread         %9.1f  (%.2fx MIEV0)\n", b.ns_batch,
                b.ns_miev0 / b.ns_batch);
  os << buf;
  const std::string label = "spheres(), " + std::to_string(b.threads) + " threads";
  std::snprintf(buf, sizeof buf, "  %-27s %9.1f  (%.2fx MIEV0 on one core, wall clock)\n", label.c_str(),
                b.ns_batch_threads, b.ns_miev0 / b.ns_batch_threads);
  os << buf;
  return os.str();
}

}  // namespace attenuvis::validation
