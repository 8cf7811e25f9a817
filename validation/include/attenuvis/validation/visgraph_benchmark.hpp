// Measurements of the visibility-graph engine that the reproduction report
// (section_performance.cpp) and the benchmark program
// (validation/bench/visgraph_throughput.cpp) share: speed as a ratio to a raw
// Embree occlusion loop over the same pairs in the same run, the extra memory
// of a pass, and S_S error against run time for range pruning.  Nothing here
// decides pass/fail: callers print or tabulate the figures.
#pragma once

#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace attenuvis::validation {

// The seed paper's printed sigmas (1/m: clear 0.00015, rain 8 mm/h 0.0045,
// advection fog 0.02874311, dry snow 4 mm/h 0.0374; Sec. Results), used as
// the "degree + 4 conditions" workload of the throughput measurements.
std::vector<double> seed_benchmark_sigmas();

// Best (minimum) wall time of `repeats` calls of one measurement, seconds.
struct Timing {
  double best_s = 0;
  double median_s = 0;
};

// Engine (all_to_all, degree + `sigmas`) against raw Embree occlusion of the
// same unordered pairs (visgraph::raw_visible_pairs), all on `threads`.
struct ThroughputOptions {
  std::vector<double> sigmas = seed_benchmark_sigmas();
  int threads = 1;
  int repeats = 3;
  bool single_rays = true;  // also time the rtcOccluded1 loop (the slowest part)
  bool brute_force = false;  // also time the engine with culling off (every pair cast)
};

// Pairs per second of the visibility pass against raw Embree occlusion rays on
// the same pairs, measured in one run.
struct Throughput {
  std::size_t nodes = 0;
  std::uint64_t pairs = 0;  // unordered pairs, N (N-1) / 2
  Timing engine, packets16, single;  // single is zero when not measured
  Timing brute;                      // engine without culling; zero when not measured
  std::uint64_t visible_engine = 0, visible_packets16 = 0, visible_single = 0, visible_brute = 0;
  // Where the engine's pairs went: decided by culling (in sight / blocked)
  // or by a ray; and the seconds spent clustering and classifying.
  std::uint64_t culled_visible = 0, culled_blocked = 0, cast = 0;
  double culling_s = 0;
  double engine_mpairs_s() const { return pairs / engine.best_s / 1e6; }
  double packets16_mpairs_s() const { return pairs / packets16.best_s / 1e6; }
  double single_mpairs_s() const { return single.best_s > 0 ? pairs / single.best_s / 1e6 : 0.0; }
  // Speed of the engine as a fraction of the raw loop's speed (1 = as fast as Embree alone).
  double ratio_to_packets16() const { return packets16.best_s / engine.best_s; }
  double ratio_to_single() const { return single.best_s > 0 ? single.best_s / engine.best_s : 0.0; }
  double ratio_brute_to_packets16() const { return brute.best_s > 0 ? packets16.best_s / brute.best_s : 0.0; }
  bool visible_agree() const;  // every method found the same number of visible pairs
};

// Measures the pass and raw Embree on `eyes` as `options` says.
Throughput measure_throughput(const visgraph::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                              const ThroughputOptions& options);

// The two floors an all-to-all pass is measured against, on the same eye
// points in the same run (docs/validation/benchmarks.md):
//  - rays: raw Embree casting every unordered pair (raw_visible_pairs,
//    16-wide packets), no scoring;
//  - scoring: raw_scoring_loop, every pair taken as in sight and scored as
//    a plain loop vectorised by the compiler, no rays.
// Returns the sum of every score (a checksum that keeps the compiler from
// dropping the work).
double raw_scoring_loop(const std::vector<Eigen::Vector3d>& eyes, const std::vector<double>& sigmas, int threads);

// CPU seconds (user + system, every thread) of this process so far.
double process_cpu_seconds();

// The conditions, threads, repeats and floors of compare_with_floors.
struct FloorOptions {
  std::vector<double> sigmas = seed_benchmark_sigmas();
  int threads = 1;
  int repeats = 1;
  bool rays_floor = true;     // raw Embree on every pair
  bool scoring_floor = true;  // raw vectorised scoring loop
  // The engine once more without its eyes' plane (VisibilityOptions::
  // eye_plane false), which decides sight lines where every node stands
  // at one height: what the plane gains, in the same run.
  bool without_eye_plane = true;
};

// The engine (all_to_all, degree + sigmas, exact with culling) and the
// floors, interleaved repeat by repeat, each timed in CPU seconds of the
// process (best of the repeats; on a shared machine CPU time moves less
// than wall time) and wall seconds; then one more engine run with
// VisibilityOptions::phase_times for where its time goes.
struct FloorComparison {
  std::size_t nodes = 0;
  std::uint64_t pairs = 0;
  std::uint64_t culled_visible = 0, culled_blocked = 0, cast = 0;  // engine: how each pair was decided
  std::uint64_t visible = 0;                                       // pairs in sight, however decided
  Timing engine_cpu, engine_wall, rays_cpu, scoring_cpu;          // zero when not measured
  Timing engine_no_plane_cpu;  // the engine without the eyes' plane (zero when not measured)
  std::uint64_t cast_no_plane = 0;  // pairs it cast
  // The engine's CPU time split by phase: clustering and classifying
  // cluster pairs, deciding packets, scoring, rays.  Estimated: each
  // phase's share of the time the phase-timed run measured in them (steady
  // clock, so on a loaded machine waiting is counted too, alike for all)
  // times engine_cpu.best_s.
  double cluster_s = 0, packet_s = 0, score_s = 0, rays_s = 0;
  // Engine speed over each floor's: rays_cpu / engine_cpu (> 1: the
  // engine beats casting every pair), and engine_cpu / scoring_cpu (the
  // engine's time as a multiple of the scoring floor's).
  double over_rays() const { return rays_cpu.best_s > 0 ? rays_cpu.best_s / engine_cpu.best_s : 0.0; }
  double over_scoring() const { return scoring_cpu.best_s > 0 ? engine_cpu.best_s / scoring_cpu.best_s : 0.0; }
  // rays_cpu / engine_no_plane_cpu: over_rays() without the eyes' plane.
  double over_rays_no_plane() const {
    return rays_cpu.best_s > 0 && engine_no_plane_cpu.best_s > 0 ? rays_cpu.best_s / engine_no_plane_cpu.best_s : 0.0;
  }
  // The most over_rays() can be for an engine that scores each pair in
  // sight as fast as the raw scoring loop does and spends nothing on any
  // other pair: raw Embree's time over the loop's time for the pairs in
  // sight alone.  The engine's scoring can come a little under the loop's
  // (its fixed-point sums run in registers), so this is an estimate, not a
  // proof; on the open plane the engine takes 0.9-1.4 times the loop's time.
  double ceiling() const {
    const double share = pairs > 0 ? static_cast<double>(visible) / static_cast<double>(pairs) : 0.0;
    return rays_cpu.best_s > 0 && scoring_cpu.best_s > 0 && share > 0 ? rays_cpu.best_s / (scoring_cpu.best_s * share)
                                                                       : 0.0;
  }
};

// The engine against raw Embree casting every pair and a raw vectorised
// scoring loop, on the same eye points, in the same run.
FloorComparison compare_with_floors(const visgraph::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                                    const FloorOptions& options);

// Extra memory of one all-to-all pass without edge output (degree + `sigmas`,
// distance statistics on), measured two ways:
//  - resident set: the kernel's peak RSS (VmHWM of /proc/self/status) during
//    the pass minus VmRSS just before it, after resetting the peak by writing
//    "5" to /proc/self/clear_refs (Linux >= 4.0); `rss_peak_reset` says
//    whether that reset worked (if not, the figure is an upper bound that
//    includes any earlier peak of the process);
//  - heap: bytes obtained through operator new, if the program counts them
//    (see AllocationCounter below); -1 otherwise.
struct MemoryUse {
  std::size_t nodes = 0;
  double rss_before_mb = 0, rss_peak_mb = 0, rss_extra_mb = 0;
  bool rss_peak_reset = false;
  double heap_peak_extra_mb = -1;  // peak live operator-new bytes above the level before the pass
  double seconds = 0;
};

// Optional hook: a program that replaces the global operator new/delete can
// report live bytes through these two functions (the benchmark does; the
// library itself never replaces allocation functions).
struct AllocationCounter {
  std::int64_t (*live_bytes)() = nullptr;
  void (*reset_peak)() = nullptr;  // peak := current live bytes
  std::int64_t (*peak_bytes)() = nullptr;
};

// Measures the memory one pass allocates (through `counter`) against its estimate.
MemoryUse measure_memory(const visgraph::Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                         const std::vector<double>& sigmas, int threads, const AllocationCounter& counter = {});

// One row of the error-against-time study: all_to_all with S_S for `sigma`
// only, at prune_below = eps, compared with the exact sums `reference` (the same
// sigma, eps = 0).
struct PruningPoint {
  double prune_below = 0;
  double radius_m = 0;          // ln(1/eps)/sigma; infinite for eps = 0
  std::uint64_t pairs_cast = 0;
  double seconds = 0;           // best of the repeats
  double max_abs_error = 0;     // max over nodes of |S_S - S_S(exact)|
  double max_bound = 0;         // max over nodes of the certified bound
  std::size_t bound_violations = 0;
};

// Times a pruned pass and measures its error against the exact `reference`.
PruningPoint measure_pruning(const visgraph::Scene& scene, const std::vector<Eigen::Vector3d>& eyes, double sigma,
                             double prune_below, const std::vector<double>& reference, int threads, int repeats);

// Resident-set figures of this process from /proc/self/status, MB (-1 if unreadable).
double proc_status_mb(const std::string& field);  // "VmRSS", "VmHWM", ...

// Machine context for a printed figure: "N hardware threads, load average a b c".
std::string machine_line();

}  // namespace attenuvis::validation
