// Error map and error-against-run-time table of the Mie core (see
// attenuvis/validation/mie_accuracy.hpp for the definitions and costs).
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/validation/mie_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "attenuvis/mie.hpp"
#include "attenuvis/mie/referee.hpp"
#include "attenuvis/validation/mie_conventional.hpp"

namespace attenuvis::validation {
namespace {

namespace mie = attenuvis::mie;

MieQuantities from(const ConventionalMieResult& r) { return {r.qext, r.qsca, r.qabs, r.g, r.qback}; }

// Keeps the optimiser from dropping calls whose results are otherwise unused.
volatile double g_sink = 0;

// Median time per call of f(), in ns.  Each sample repeats f() until it lasts at
// least min_seconds (calibrated on one call), so clock resolution does not matter.
template <class F>
double median_ns_per_call(F&& f, double min_seconds, int samples) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  g_sink = g_sink + f();
  const double once = std::chrono::duration<double>(clock::now() - t0).count();
  const long reps = std::max<long>(1, static_cast<long>(std::ceil(min_seconds / std::max(once, 1e-9))));
  std::vector<double> per_call;
  for (int s = 0; s < std::max(1, samples); ++s) {
    double acc = 0;
    t0 = clock::now();
    for (long i = 0; i < reps; ++i) acc += f();
    const double dt = std::chrono::duration<double>(clock::now() - t0).count();
    g_sink = g_sink + acc;
    per_call.push_back(dt / static_cast<double>(reps) * 1e9);
  }
  std::sort(per_call.begin(), per_call.end());
  return per_call[per_call.size() / 2];
}

}  // namespace

double mie_max_relative_error(const MieQuantities& got, const MieQuantities& ref) {
  const double floor = 1e-4 * std::abs(ref.qext);
  const double pairs[5][2] = {{got.qext, ref.qext},
                              {got.qsca, ref.qsca},
                              {got.qabs, ref.qabs},
                              {got.g, ref.g},
                              {got.qback, ref.qback}};
  double worst = 0;
  for (const auto& p : pairs) {
    if (!std::isfinite(p[0])) return std::numeric_limits<double>::infinity();
    const double denom = std::max(std::abs(p[1]), floor);
    const double e = denom > 0 ? std::abs(p[0] - p[1]) / denom
                               : (p[0] == 0 ? 0.0 : std::numeric_limits<double>::infinity());
    worst = std::max(worst, e);
  }
  return worst;
}

MieQuantities mie_quantities(const mie::Efficiencies<double>& e) { return {e.qext, e.qsca, e.qabs, e.g, e.qback}; }

MieQuantities mie_referee_quantities(double x, std::complex<double> m) {
  const auto r = mie::sphere_referee(x, m);
  return {r.qext.convert_to<double>(), r.qsca.convert_to<double>(), r.qabs.convert_to<double>(),
          r.g.convert_to<double>(), r.qback.convert_to<double>()};
}

std::vector<ErrorMapCell> mie_error_map(const std::vector<double>& xs,
                                        const std::vector<std::complex<double>>& ms) {
  std::vector<ErrorMapCell> cells;
  cells.reserve(xs.size() * ms.size());
  for (const auto& m : ms)
    for (double x : xs) {
      const MieQuantities ref = mie_referee_quantities(x, m);
      const MieQuantities got = mie_quantities(mie::sphere(x, m));
      cells.push_back({x, m.real(), m.imag(), mie_max_relative_error(got, ref)});
    }
  return cells;
}

ErrorTimeOptions quick_error_time_options() {
  ErrorTimeOptions o;
  o.max_x = 1e4;
  o.samples = 3;
  o.min_sample_seconds = 1e-3;
  return o;
}

std::vector<ErrorTimeRow> mie_error_vs_time(const ErrorTimeOptions& options) {
  std::vector<ErrorTimeRow> rows;
  mie::Options wiscombe;
  wiscombe.terms = mie::TermRule::wiscombe;
  mie::Options fast;
  fast.precision = mie::Precision::double_precision;
  for (const auto& m : options.ms)
    for (double x : options.xs) {
      if (!(x > 0) || x > options.max_x) continue;
      const MieQuantities ref = mie_referee_quantities(x, m);

      const auto def = mie::sphere(x, m);
      rows.push_back({x, m, "default",
                      median_ns_per_call([&] { return mie::sphere(x, m).qext; },
                                         options.min_sample_seconds, options.samples),
                      mie_max_relative_error(mie_quantities(def), ref), static_cast<int>(def.terms)});

      const auto dbl = mie::sphere(x, m, fast);
      rows.push_back({x, m, "double",
                      median_ns_per_call([&] { return mie::sphere(x, m, fast).qext; },
                                         options.min_sample_seconds, options.samples),
                      mie_max_relative_error(mie_quantities(dbl), ref), static_cast<int>(dbl.terms)});

      const auto wis = mie::sphere(x, m, wiscombe);
      rows.push_back({x, m, "wiscombe",
                      median_ns_per_call([&] { return mie::sphere(x, m, wiscombe).qext; },
                                         options.min_sample_seconds, options.samples),
                      mie_max_relative_error(mie_quantities(wis), ref), static_cast<int>(wis.terms)});

      if (options.include_conventional) {
        const auto conv = conventional_bhmie(x, m);
        rows.push_back({x, m, "conventional",
                        median_ns_per_call([&] { return conventional_bhmie(x, m).qext; },
                                           options.min_sample_seconds, options.samples),
                        mie_max_relative_error(from(conv), ref), conv.terms});
      }
    }
  return rows;
}

void write_error_vs_time_csv(const std::string& path, const std::vector<ErrorTimeRow>& rows) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const fs::path tmp = target.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << "x,m_re,m_im,mode,ns_per_call,max_rel_error,terms\n" << std::setprecision(17);
    for (const auto& r : rows)
      out << r.x << ',' << r.m.real() << ',' << r.m.imag() << ',' << r.mode << ','
          << std::setprecision(6) << r.ns_per_call << ',' << std::setprecision(3) << r.max_rel_error
          << ',' << r.terms << std::setprecision(17) << '\n';
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp);
      throw std::runtime_error("error while writing " + tmp.string());
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot replace " + target.string() + ": " + ec.message());
  }
}

std::string format_error_vs_time(const std::vector<ErrorTimeRow>& rows) {
  // Group rows by (m, x) in first-seen order; columns per mode.
  std::vector<std::pair<std::complex<double>, double>> keys;
  std::map<std::pair<std::string, double>, std::map<std::string, const ErrorTimeRow*>> by;
  for (const auto& r : rows) {
    const auto key = std::make_pair(io::index_text(r.m), r.x);
    if (by.find(key) == by.end()) keys.emplace_back(r.m, r.x);
    by[key][r.mode] = &r;
  }
  const char* modes[] = {"default", "double", "wiscombe", "conventional"};
  std::ostringstream os;
  char line[256];
  std::snprintf(line, sizeof line, "%-12s %8s | %10s %9s | %10s %9s | %10s %9s | %10s %9s | %8s\n", "m", "x",
                "default ns", "error", "double ns", "error", "wiscombe", "error", "convent.", "error", "def/conv");
  os << line << std::string(std::string(line).size() - 1, '-') << '\n';
  for (const auto& [m, x] : keys) {
    const auto& cols = by[{io::index_text(m), x}];
    std::snprintf(line, sizeof line, "%-12s %8.0e |", io::index_text(m).c_str(), x);
    os << line;
    for (const char* mode : modes) {
      const auto it = cols.find(mode);
      if (it == cols.end()) {
        std::snprintf(line, sizeof line, " %10s %9s |", "-", "-");
      } else {
        std::snprintf(line, sizeof line, " %10.4g %9.1e |", it->second->ns_per_call,
                      it->second->max_rel_error);
      }
      os << line;
    }
    const auto d = cols.find("default"), c = cols.find("conventional");
    if (d != cols.end() && c != cols.end())
      std::snprintf(line, sizeof line, " %8.2f\n", d->second->ns_per_call / c->second->ns_per_call);
    else
      std::snprintf(line, sizeof line, " %8s\n", "-");
    os << line;
  }
  return os.str();
}

std::string timing_machine_description() {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  std::string l;
  while (std::getline(info, l))
    if (l.rfind("model name", 0) == 0) {
      const auto colon = l.find(':');
      if (colon != std::string::npos) cpu = l.substr(colon + 2);
      break;
    }
  // Timings on a shared machine are only as good as its load; say what it was.
  std::string load = "?";
  std::ifstream loadavg("/proc/loadavg");
  if (loadavg) loadavg >> load;
  std::ostringstream os;
  os << cpu << ", " << std::thread::hardware_concurrency() << " hardware threads, 1-minute load "
     << load << " at the time of the call, single-threaded timings; compiler " <<
#if defined(__clang__)
      "clang "
#elif defined(__GNUC__)
      "gcc "
#endif
     << __VERSION__;
  return os.str();
}

}  // namespace attenuvis::validation
