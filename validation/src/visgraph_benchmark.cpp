// Shared measurements of the visibility-graph engine (see
// attenuvis/validation/visgraph_benchmark.hpp).
#include <attenuvis/validation/visgraph_benchmark.hpp>
#include <attenuvis/visgraph/detail/raw_occlusion.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <sys/resource.h>

namespace attenuvis::validation {

namespace vg = attenuvis::visgraph;

namespace {
template <class F>
Timing time_repeats(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2]};
}
}  // namespace

std::vector<double> seed_benchmark_sigmas() { return {0.00015, 0.0045, 0.02874311, 0.0374}; }

bool Throughput::visible_agree() const {
  // The engine decides each pair by its own ray (rtcOccluded1) or by culling
  // with a margin: it agrees with the single-ray loop and with itself
  // without culling.  The packet loop may differ on sight lines that graze
  // an edge (Embree's packet and single-ray traversals round differently).
  return (single.best_s == 0 || visible_single == visible_engine) && (brute.best_s == 0 || visible_brute == visible_engine);
}

Throughput measure_throughput(const vg::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                              const ThroughputOptions& options) {
  Throughput out;
  out.nodes = eyes.size();
  vg::VisibilityOptions o;
  o.sigmas = options.sigmas;
  o.threads = options.threads;
  vg::VisibilityResult result;
  // Interleave engine and raw loop repeat by repeat so that a change of load
  // on a shared machine hits both alike.
  std::vector<double> te, tp;
  for (int r = 0; r < std::max(1, options.repeats); ++r) {
    te.push_back(time_repeats(1, [&] { result = vg::all_to_all(scene, eyes, o); }).best_s);
    tp.push_back(time_repeats(1, [&] {
                   out.visible_packets16 = vg::raw_visible_pairs(scene, eyes, options.threads, vg::RawMethod::packets16);
                 }).best_s);
  }
  std::sort(te.begin(), te.end());
  std::sort(tp.begin(), tp.end());
  out.engine = {te.front(), te[te.size() / 2]};
  out.packets16 = {tp.front(), tp[tp.size() / 2]};
  out.pairs = result.pairs_total;
  out.visible_engine = result.pairs_visible;
  out.culled_visible = result.pairs_culled_visible;
  out.culled_blocked = result.pairs_culled_blocked;
  out.cast = result.pairs_cast;
  out.culling_s = result.culling_seconds;
  if (options.brute_force) {
    vg::VisibilityOptions b = o;
    b.culling = false;
    out.brute = time_repeats(1, [&] { out.visible_brute = vg::all_to_all(scene, eyes, b).pairs_visible; });
  }
  if (options.single_rays)
    out.single = time_repeats(1, [&] {
      out.visible_single = vg::raw_visible_pairs(scene, eyes, options.threads, vg::RawMethod::single_rays);
    });
  return out;
}

double process_cpu_seconds() {
  rusage use{};
  getrusage(RUSAGE_SELF, &use);
  return static_cast<double>(use.ru_utime.tv_sec + use.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(use.ru_utime.tv_usec + use.ru_stime.tv_usec);
}

namespace {
// Best and median of a list of seconds.
Timing best_and_median(std::vector<double> t) {
  if (t.empty()) return {};
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2]};
}

// Runs f once; appends its CPU and wall seconds.
template <class F>
void time_cpu(std::vector<double>& cpu, std::vector<double>* wall, F&& f) {
  const double c0 = process_cpu_seconds();
  const auto w0 = std::chrono::steady_clock::now();
  f();
  cpu.push_back(process_cpu_seconds() - c0);
  if (wall) wall->push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
}
}  // namespace

FloorComparison compare_with_floors(const vg::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                                    const FloorOptions& options) {
  FloorComparison out;
  out.nodes = eyes.size();
  vg::VisibilityOptions o;
  o.sigmas = options.sigmas;
  o.threads = options.threads;
  vg::VisibilityResult result;
  std::vector<double> engine_cpu, engine_wall, rays_cpu, scoring_cpu, no_plane_cpu;
  volatile double keep = 0;
  vg::VisibilityOptions without = o;
  without.eye_plane = false;
  for (int r = 0; r < std::max(1, options.repeats); ++r) {
    time_cpu(engine_cpu, &engine_wall, [&] { result = vg::all_to_all(scene, eyes, o); });
    if (options.without_eye_plane)
      time_cpu(no_plane_cpu, nullptr, [&] { out.cast_no_plane = vg::all_to_all(scene, eyes, without).pairs_cast; });
    if (options.rays_floor)
      time_cpu(rays_cpu, nullptr, [&] {
        keep = keep + static_cast<double>(vg::raw_visible_pairs(scene, eyes, options.threads, vg::RawMethod::packets16));
      });
    if (options.scoring_floor)
      time_cpu(scoring_cpu, nullptr, [&] { keep = keep + raw_scoring_loop(eyes, options.sigmas, options.threads); });
  }
  out.engine_cpu = best_and_median(engine_cpu);
  out.engine_wall = best_and_median(engine_wall);
  out.rays_cpu = best_and_median(rays_cpu);
  out.scoring_cpu = best_and_median(scoring_cpu);
  out.engine_no_plane_cpu = best_and_median(no_plane_cpu);
  out.pairs = result.pairs_total;
  out.culled_visible = result.pairs_culled_visible;
  out.culled_blocked = result.pairs_culled_blocked;
  out.cast = result.pairs_cast;
  out.visible = result.pairs_visible;
  o.phase_times = true;
  const vg::VisibilityResult phases = vg::all_to_all(scene, eyes, o);
  // Clustering runs on the pass's threads: its wall time counts for each.
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  const double cluster = phases.culling_seconds * threads;
  const double timed = cluster + phases.packet_culling_seconds + phases.score_seconds + phases.ray_seconds;
  const double scale = timed > 0 ? out.engine_cpu.best_s / timed : 0.0;
  out.cluster_s = cluster * scale;
  out.packet_s = phases.packet_culling_seconds * scale;
  out.score_s = phases.score_seconds * scale;
  out.rays_s = phases.ray_seconds * scale;
  return out;
}

double proc_status_mb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, field.size() + 1, field + ":") != 0) continue;
    std::istringstream value(line.substr(field.size() + 1));
    double kb = -1;
    value >> kb;
    return kb < 0 ? -1 : kb / 1024.0;
  }
  return -1;
}

MemoryUse measure_memory(const vg::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                         const std::vector<double>& sigmas, int threads, const AllocationCounter& counter) {
  MemoryUse m;
  m.nodes = eyes.size();
  vg::VisibilityOptions o;
  o.sigmas = sigmas;
  o.threads = threads;
  o.distance_stats = true;
  // Warm-up on a few nodes: starts the TBB workers (their stacks are not the
  // pass's memory) and Embree's per-thread state.
  {
    const std::vector<Eigen::Vector3d> few(eyes.begin(), eyes.begin() + std::min<std::size_t>(eyes.size(), 64));
    vg::all_to_all(scene, few, o);
  }
  {
    std::ofstream reset("/proc/self/clear_refs");
    reset << "5" << std::flush;  // resets VmHWM to the current RSS
    m.rss_peak_reset = static_cast<bool>(reset);
  }
  m.rss_before_mb = proc_status_mb("VmRSS");
  const double hwm_before = proc_status_mb("VmHWM");
  if (m.rss_peak_reset && hwm_before > m.rss_before_mb + 0.5) m.rss_peak_reset = false;  // the reset did not take
  std::int64_t live_before = 0;
  if (counter.live_bytes && counter.reset_peak && counter.peak_bytes) {
    live_before = counter.live_bytes();
    counter.reset_peak();
  }
  const auto t0 = std::chrono::steady_clock::now();
  {
    const vg::VisibilityResult result = vg::all_to_all(scene, eyes, o);
    m.rss_peak_mb = proc_status_mb("VmHWM");
    (void)result;
  }
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.rss_extra_mb = m.rss_peak_mb - m.rss_before_mb;
  if (counter.peak_bytes && counter.reset_peak && counter.live_bytes)
    m.heap_peak_extra_mb = static_cast<double>(counter.peak_bytes() - live_before) / (1024.0 * 1024.0);
  return m;
}

PruningPoint measure_pruning(const vg::Scene& scene, const std::vector<Eigen::Vector3d>& eyes, double sigma,
                             double prune_below, const std::vector<double>& reference, int threads, int repeats) {
  if (reference.size() != eyes.size()) throw std::invalid_argument("measure_pruning: reference has the wrong size");
  vg::VisibilityOptions o;
  o.sigmas = {sigma};
  o.prune_below = prune_below;
  o.threads = threads;
  vg::VisibilityResult r;
  PruningPoint p;
  p.prune_below = prune_below;
  p.seconds = time_repeats(repeats, [&] { r = vg::all_to_all(scene, eyes, o); }).best_s;
  p.radius_m = r.pruning_radius;
  p.pairs_cast = r.pairs_cast;
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    const double err = std::abs(r.sum[0][i] - reference[i]);
    const double bound = r.sum_error_bound(i);
    p.max_abs_error = std::max(p.max_abs_error, err);
    p.max_bound = std::max(p.max_bound, bound);
    if (err > bound) ++p.bound_violations;
  }
  return p;
}

std::string machine_line() {
  std::ostringstream s;
  s << std::thread::hardware_concurrency() << " hardware threads";
  std::ifstream load("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (load >> a >> b >> c) s << ", load average " << a << " " << b << " " << c;
  return s.str();
}

}  // namespace attenuvis::validation
