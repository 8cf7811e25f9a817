// The current Mie core against an earlier build of itself (see
// attenuvis/validation/mie_baseline.hpp).
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/validation/mie_baseline.hpp"
#include "block_timing.hpp"
#include "core_batch.hpp"

#include <algorithm>
#include <cstring>
#include <random>
#include <thread>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/spheres.hpp"

namespace attenuvis::validation {
namespace {

namespace mie = attenuvis::mie;
using timing::block_ns;

}  // namespace

MieBaseline::MieBaseline(const std::string& library_path)
    : library_(library_path, "the baseline Mie library", "attenuvis_mie_baseline_sphere",
               "validation/bench/baseline/build_mie_baseline.sh") {}

MieQuantities MieBaseline::sphere(double x, std::complex<double> m, int* terms) const {
  double q[6];
  using Entry = int (*)(double x, double m_re, double m_im, double* q);
  if (reinterpret_cast<Entry>(library_.entry())(x, m.real(), m.imag(), q) != 0)
    throw std::runtime_error("baseline Mie core threw");
  if (terms) *terms = static_cast<int>(q[5]);
  return {q[0], q[1], q[2], q[4], q[3]};
}

std::vector<SpeedCell> mie_speed_vs_baseline(const MieBaseline& baseline, const SpeedOptions& options) {
  std::vector<SpeedCell> cells;
  for (double x : options.xs)
    for (const auto& m : options.ms) {
      SpeedCell c;
      c.x = x;
      c.m = m;
      const auto ns = timing::alternating_min_ns(
          options.min_block_seconds, options.blocks, [&] { return mie::sphere(x, m).qext; },
          [&] { return baseline.sphere(x, m).qext; });
      c.ns_current = ns[0], c.ns_baseline = ns[1];
      const auto e = mie::sphere(x, m);
      c.terms_current = static_cast<int>(e.terms);
      const MieQuantities old = baseline.sphere(x, m, &c.terms_baseline);
      if (x <= options.max_referee_x) {
        const MieQuantities ref = mie_referee_quantities(x, m);
        c.err_current = mie_max_relative_error(mie_quantities(e), ref);
        c.err_baseline = mie_max_relative_error(old, ref);
      }
      cells.push_back(c);
    }
  return cells;
}

std::vector<double> batch_size_parameters(double x_min, double x_max, std::size_t count) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> u(x_min, x_max);
  std::vector<double> x(count);
  for (double& v : x) v = u(rng);
  return x;
}

unsigned batch_threads(unsigned requested) {
  return requested ? requested : std::max(1u, std::thread::hardware_concurrency());
}

CoreBatch::CoreBatch(const std::vector<double>& x, std::complex<double> m, unsigned threads)
    : x_(x), m_(m), threads_(threads), out_(x.size()) {}

double CoreBatch::run(unsigned threads) {
  mie::SpheresOptions o;
  o.threads = threads;
  mie::spheres(x_.data(), m_, x_.size(), out_.data(), o);
  return out_[0].qext;
}

BatchSpeed mie_batch_vs_baseline(const MieBaseline& baseline, BatchSpeed b, int blocks) {
  const std::vector<double> x = batch_size_parameters(b.x_min, b.x_max, b.count);
  std::vector<mie::Efficiencies<double>> single(b.count);
  b.threads = batch_threads(b.threads);
  CoreBatch core(x, b.m, b.threads);
  const double n = static_cast<double>(b.count);
  auto run_base = [&] {
    double acc = 0;
    for (double xi : x) acc += baseline.sphere(xi, b.m).qext;
    return acc;
  };
  auto run_single = [&] {
    for (std::size_t i = 0; i < b.count; ++i) single[i] = mie::sphere(x[i], b.m);
    return single[0].qext;
  };
  auto run_batch = [&] { return core.one_thread(); };
  auto run_threads = [&] { return core.all_threads(); };
  b.ns_baseline = b.ns_single = b.ns_batch = b.ns_batch_threads = std::numeric_limits<double>::infinity();
  b.instruction_sets = mie::spheres_instruction_sets();
  b.ns_batch_by_set.assign(b.instruction_sets.size(), std::numeric_limits<double>::infinity());
  std::vector<mie::Efficiencies<double>> by_set(b.count);
  b.identical_by_set = true;
  for (int k = 0; k < std::max(1, blocks); ++k) {
    for (std::size_t s = 0; s < b.instruction_sets.size(); ++s) {
      mie::SpheresOptions o;
      o.threads = 1;
      o.instruction_set = b.instruction_sets[s];
      auto run_set = [&] {
        mie::spheres(x.data(), b.m, b.count, by_set.data(), o);
        return by_set[0].qext;
      };
      b.ns_batch_by_set[s] = std::min(b.ns_batch_by_set[s], block_ns(run_set, 1) / n);
      if (k == 0) {
        for (std::size_t i = 0; i < b.count; ++i) single[i] = mie::sphere(x[i], b.m);
        b.identical_by_set =
            b.identical_by_set && std::memcmp(single.data(), by_set.data(), sizeof(single[0]) * b.count) == 0;
      }
    }
    b.ns_baseline = std::min(b.ns_baseline, block_ns(run_base, 1) / n);
    b.ns_single = std::min(b.ns_single, block_ns(run_single, 1) / n);
    b.ns_batch = std::min(b.ns_batch, block_ns(run_batch, 1) / n);
    b.ns_batch_threads = std::min(b.ns_batch_threads, timing::wall_block_ns(run_threads, 1) / n);
  }
  b.identical = std::memcmp(single.data(), core.results().data(), sizeof(single[0]) * b.count) == 0;
  return b;
}

std::string format_batch_speed(const BatchSpeed& b) {
  std::ostringstream os;
  char buf[200];
  os << "many spheres: " << b.count << " x uniform in [" << b.x_min << ", " << b.x_max << "], m = "
     << io::index_text(b.m) << " (ns per sphere, minimum over blocks)\n";
  std::snprintf(buf, sizeof buf, "  baseline sphere() loop      %9.1f\n", b.ns_baseline);
  os << buf;
  std::snprintf(buf, sizeof buf, "  current sphere() loop       %9.1f  (%.2fx)\n", b.ns_single, b.ns_baseline / b.ns_single);
  os << buf;
  std::snprintf(buf, sizeof buf, "  current spheres(), 1 thread %9.1f  (%.2fx)\n", b.ns_batch, b.ns_baseline / b.ns_batch);
  os << buf;
  std::snprintf(buf, sizeof buf, "  current spheres(), %u threads %7.1f  (%.2fx, wall clock)\n", b.threads,
                b.ns_batch_threads, b.ns_baseline / b.ns_batch_threads);
  os << buf;
  os << "  spheres() " << (b.identical ? "equals" : "DIFFERS FROM") << " sphere() bit for bit on every sphere\n";
  if (!b.instruction_sets.empty()) {
    os << "spheres(), 1 thread, by vector instruction set (the first is chosen on this CPU):\n";
    for (std::size_t s = 0; s < b.instruction_sets.size(); ++s) {
      std::snprintf(buf, sizeof buf, "  %-8s %9.1f  (%.2fx)\n", b.instruction_sets[s].c_str(), b.ns_batch_by_set[s],
                    b.ns_baseline / b.ns_batch_by_set[s]);
      os << buf;
    }
    os << "  every instruction set " << (b.identical_by_set ? "gives" : "DOES NOT give") << " sphere()'s bits\n";
  }
  return os.str();
}

std::string measured_error_text(double err) {
  if (!(err >= 0)) return "-";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.1e", err);
  return buf;
}

std::string format_speed_vs_baseline(const std::vector<SpeedCell>& cells, const std::string& baseline_name) {
  std::vector<std::complex<double>> ms;
  std::vector<double> xs;
  std::map<std::pair<double, std::string>, const SpeedCell*> at;
  for (const auto& c : cells) {
    if (std::find(ms.begin(), ms.end(), c.m) == ms.end()) ms.push_back(c.m);
    if (std::find(xs.begin(), xs.end(), c.x) == xs.end()) xs.push_back(c.x);
    at[{c.x, io::index_text(c.m)}] = &c;
  }
  std::ostringstream os;
  char buf[256];
  os << "speed-up = " << baseline_name << " time / current time per call (same run, alternating blocks, "
     << "thread CPU time, minimum over blocks); err = max relative error against the 50-digit referee (current / baseline)\n";
  for (const auto& m : ms) {
    std::snprintf(buf, sizeof buf, "\nm = %s\n%8s %12s %12s %9s %10s %10s %7s\n", io::index_text(m).c_str(), "x",
                  "current ns", "baseline ns", "speed-up", "err", "err base", "terms");
    os << buf;
    for (double x : xs) {
      const auto it = at.find({x, io::index_text(m)});
      if (it == at.end()) continue;
      const SpeedCell& c = *it->second;
      std::snprintf(buf, sizeof buf, "%8.0e %12.4g %12.4g %9.2f %10s %10s %7d\n", x, c.ns_current, c.ns_baseline,
                    c.speedup(), measured_error_text(c.err_current).c_str(),
                    measured_error_text(c.err_baseline).c_str(), c.terms_current);
      os << buf;
    }
  }
  os << "\nspeed-up by x (rows) and index (columns)\n";
  std::snprintf(buf, sizeof buf, "%8s", "x");
  os << buf;
  for (const auto& m : ms) {
    std::snprintf(buf, sizeof buf, " %12s", io::index_text(m).c_str());
    os << buf;
  }
  os << '\n';
  for (double x : xs) {
    std::snprintf(buf, sizeof buf, "%8.0e", x);
    os << buf;
    for (const auto& m : ms) {
      const auto it = at.find({x, io::index_text(m)});
      if (it == at.end()) std::snprintf(buf, sizeof buf, " %12s", "-");
      else std::snprintf(buf, sizeof buf, " %11.2fx", it->second->speedup());
      os << buf;
    }
    os << '\n';
  }
  return os.str();
}

}  // namespace attenuvis::validation
