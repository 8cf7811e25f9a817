// Benchmark of the visibility-graph engine:
//  1. pairs/s of all_to_all with degree + 4 conditions against a raw Embree
//     occlusion loop over the same unordered pairs, in the same run
//     (visgraph::raw_visible_pairs: 16-wide packets and single rays), on the
//     five classic layouts at 1 m and 0.5 m and on the synthetic city, for
//     each thread count; the ratio engine / raw is the figure of merit;
//  2. the city all-to-all time, exact and with range pruning;
//  3. the extra memory of an all-to-all at ~10,000 nodes without edge output
//     (peak RSS from /proc/self/status, and operator-new bytes counted here);
//  4. S_S error against run time for eps in {0, 1e-12, 1e-9, 1e-6, 1e-3};
//  5. the floors: on an open plane (every pair in sight; 1 and 4
//     conditions), the Delfshaven CityJSON (real LoD2 buildings) and the
//     five layouts, the engine against raw Embree casting every pair and
//     against a raw vectorised scoring loop, in CPU seconds, with the pairs
//     culled in sight / blocked / cast and the time in classification,
//     scoring and rays.
//
// Usage: visgraph_throughput [--quick] [--threads 1,2] [--repeats N]
//                            [--city-rings N] [--no-city] [--no-single] [--brute] [--no-pruning]
//                            [--floors-only] [--no-floors] [--plane M] [--cityjson PATH] [--cityjson-spacing S]
// --brute: also time the engine with culling off (every pair cast);
// --no-pruning: skip the error-against-time study;
// --floors-only / --no-floors: run only / skip study 5; --plane: side of
// the open plane (m, 1 m grid; default 200, quick 100); --cityjson: the
// Delfshaven file (default ../shared/data/cityjson/ next to the source
// tree; skipped when absent), at --cityjson-spacing m (default 3, the
// CLI's default spacing there; quick 8).
// --quick: 1 m layouts only, one repeat, a one-ring city, no single-ray loop
// on the city, the small floors workloads (a few minutes on two cores).
#include <attenuvis/validation/visgraph_benchmark.hpp>
#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <malloc.h>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

// ---------------------------------------------------------------------------
// Counting operator new/delete (this program only): live and peak bytes of
// every C++ heap allocation in the process, the visgraph library's included.
// Sizes come from malloc_usable_size, so an allocation is counted at what the
// allocator really handed out.  Embree's own aligned allocations (BVH) and
// TBB's scalable allocator bypass operator new; the scene is built before the
// measured pass, so neither belongs to it.
namespace {
std::atomic<std::int64_t> g_live{0}, g_peak{0};

void note_alloc(void* p) {
  if (!p) return;
  const std::int64_t now = g_live.fetch_add(static_cast<std::int64_t>(malloc_usable_size(p))) +
                           static_cast<std::int64_t>(malloc_usable_size(p));
  std::int64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
  }
}
void note_free(void* p) {
  if (p) g_live.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)));
}
void* counted_alloc(std::size_t size, std::size_t align) {
  void* p = nullptr;
  if (align <= alignof(std::max_align_t)) p = std::malloc(size ? size : 1);
  else if (posix_memalign(&p, align, size ? size : 1) != 0) p = nullptr;
  if (!p) throw std::bad_alloc();
  note_alloc(p);
  return p;
}
void counted_free(void* p) {
  note_free(p);
  std::free(p);
}
}  // namespace

void* operator new(std::size_t n) { return counted_alloc(n, 0); }
void* operator new[](std::size_t n) { return counted_alloc(n, 0); }
void* operator new(std::size_t n, std::align_val_t a) { return counted_alloc(n, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_alloc(n, static_cast<std::size_t>(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_alloc(n, 0);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_alloc(n, 0);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }

namespace {
namespace vg = attenuvis::visgraph;
namespace val = attenuvis::validation;

struct Args {
  bool quick = false;
  std::vector<int> threads = {1, 2};
  int repeats = 3;
  int city_rings = 4;  // CityOptions default: ~50,000 nodes
  bool city = true;
  bool single = true;
  bool brute = false;  // also time the engine with culling off
  bool pruning = true;  // the error-against-time study on the city
  bool floors = true, floors_only = false;
  double plane = 200;
  std::string cityjson = ATTENUVIS_SHARED_DATA_DIR "/cityjson/rotterdam-delfshaven-3-20.city.json";
  double cityjson_spacing = 3;
};

double parse_positive(const std::string& text) {
  std::size_t used = 0;
  const double v = std::stod(text, &used);
  if (used != text.size() || !(v > 0)) throw std::invalid_argument("expected a positive number, got '" + text + "'");
  return v;
}

std::vector<int> parse_int_list(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    const int v = std::stoi(part, &used);
    if (used != part.size() || v < 1) throw std::invalid_argument("expected positive integers, got '" + text + "'");
    out.push_back(v);
  }
  return out;
}

Args parse(int argc, char** argv) {
  Args a;
  bool rings_given = false, repeats_given = false, plane_given = false, spacing_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(s + " needs a value");
      return argv[++i];
    };
    if (s == "--quick") a.quick = true;
    else if (s == "--threads") a.threads = parse_int_list(value());
    else if (s == "--repeats") a.repeats = parse_int_list(value()).at(0), repeats_given = true;
    else if (s == "--city-rings") a.city_rings = parse_int_list(value()).at(0), rings_given = true;
    else if (s == "--no-city") a.city = false;
    else if (s == "--no-single") a.single = false;
    else if (s == "--brute") a.brute = true;
    else if (s == "--no-pruning") a.pruning = false;
    else if (s == "--floors-only") a.floors_only = true;
    else if (s == "--no-floors") a.floors = false;
    else if (s == "--plane") a.plane = parse_positive(value()), plane_given = true;
    else if (s == "--cityjson") a.cityjson = value();
    else if (s == "--cityjson-spacing") a.cityjson_spacing = parse_positive(value()), spacing_given = true;
    else if (s == "--help" || s == "-h") {
      std::cout << "usage: visgraph_throughput [--quick] [--threads 1,2] [--repeats N] [--city-rings N] [--no-city] "
                   " [--no-single] [--brute] [--no-pruning] [--floors-only] [--no-floors] [--plane M] [--cityjson PATH]"
                   " [--cityjson-spacing S]\n";
      std::exit(0);
    } else throw std::invalid_argument("unknown argument '" + s + "'");
  }
  if (a.quick) {
    if (!repeats_given) a.repeats = 1;
    if (!rings_given) a.city_rings = 1;
    if (!plane_given) a.plane = 100;
    if (!spacing_given) a.cityjson_spacing = 8;
  }
  return a;
}

std::vector<Eigen::Vector3d> grid_nodes(const vg::Scene& scene, double spacing, std::vector<std::string> walkable) {
  vg::NodeGridOptions o;
  o.spacing = spacing;
  o.walkable = std::move(walkable);
  return vg::generate_nodes(scene, o).eyes;
}

void print_throughput_header() {
  std::printf("%-17s %7s %6s %11s %3s %9s %9s %9s %8s %8s %7s %7s %7s %7s %8s %s\n", "scene", "spacing", "nodes",
              "pairs", "thr", "engine", "raw16", "raw1", "eng/16", "eng/1", "in-sight", "blocked", "rays", "cull s",
              "brute/16", "visible agree");
  std::printf("%-17s %7s %6s %11s %3s %9s %9s %9s %8s %8s %7s %7s %7s %7s %8s\n", "", "[m]", "", "", "", "[Mp/s]",
              "[Mp/s]", "[Mp/s]", "", "", "[%]", "[%]", "[%]", "[s]", "");
}

void print_throughput(const std::string& name, double spacing, int threads, const val::Throughput& t) {
  char raw1[32] = "-", ratio1[32] = "-";
  if (t.single.best_s > 0) {
    std::snprintf(raw1, sizeof raw1, "%9.1f", t.single_mpairs_s());
    std::snprintf(ratio1, sizeof ratio1, "%8.2f", t.ratio_to_single());
  }
  char brute[32] = "-";
  if (t.brute.best_s > 0) std::snprintf(brute, sizeof brute, "%8.2f", t.ratio_brute_to_packets16());
  const double percent = 100.0 / static_cast<double>(std::max<std::uint64_t>(t.pairs, 1));
  std::printf("%-17s %7.2f %6zu %11llu %3d %9.1f %9.1f %9s %8.2f %8s %7.1f %7.1f %7.1f %7.2f %8s %s\n", name.c_str(),
              spacing, t.nodes, static_cast<unsigned long long>(t.pairs), threads, t.engine_mpairs_s(),
              t.packets16_mpairs_s(), raw1, t.ratio_to_packets16(), ratio1, t.culled_visible * percent,
              t.culled_blocked * percent, t.cast * percent, t.culling_s, brute,
              t.visible_agree() ? "yes" : ("NO: engine " + std::to_string(t.visible_engine) + ", raw16 " +
                                           std::to_string(t.visible_packets16) + ", raw1 " +
                                           std::to_string(t.visible_single))
                                              .c_str());
  std::fflush(stdout);
}

int max_threads(const Args& a) { return *std::max_element(a.threads.begin(), a.threads.end()); }

void print_workload(const Args& a) {
  std::printf("visgraph_throughput: %s; repeats %d (best of), threads", val::machine_line().c_str(), a.repeats);
  for (int t : a.threads) std::printf(" %d", t);
  std::printf("\nworkload: degree + S_S for 4 sigmas (seed paper's printed values 0.00015, 0.0045, 0.02874311, "
              "0.0374 1/m) in one pass\n");
  std::printf("raw16 = rtcOccluded16 loop over the same pairs (coherent rows), raw1 = rtcOccluded1 per pair; "
              "eng/16 = engine speed / raw16 speed\n\n");
}

// 3. The extra memory of an all-to-all on layout 2 at 0.5 m (run first, while
// the process is small; the peak is reset anyway).
void memory_study(const Args& a) {
  const vg::Scene scene(vg::classic_layout(2));
  const auto eyes = grid_nodes(scene, 0.5, vg::classic_layout_walkable_groups());
  val::AllocationCounter counter;
  counter.live_bytes = [] { return g_live.load(); };
  counter.reset_peak = [] { g_peak.store(g_live.load()); };
  counter.peak_bytes = [] { return g_peak.load(); };
  const int th = max_threads(a);
  const val::MemoryUse m = val::measure_memory(scene, eyes, val::seed_benchmark_sigmas(), th, counter);
  std::printf("memory: all-to-all on layout 2 at 0.5 m (%zu nodes), degree + 4 sigmas + distance statistics, no "
              "edge output, %d thread(s), %.2f s\n",
              m.nodes, th, m.seconds);
  std::printf("  peak RSS during the pass - RSS before: %.2f MB (VmHWM %.2f MB - VmRSS %.2f MB; peak %s)\n",
              m.rss_extra_mb, m.rss_peak_mb, m.rss_before_mb,
              m.rss_peak_reset ? "reset via /proc/self/clear_refs before the pass"
                               : "NOT resettable here: upper bound including earlier peaks");
  std::printf("  peak live operator-new bytes above the level before the pass: %.2f MB\n\n", m.heap_peak_extra_mb);
}

// 1. The classic layouts, every spacing and thread count.
void layout_throughput(const Args& a) {
  const std::vector<double> spacings = a.quick ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.5};
  print_throughput_header();
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const vg::Scene scene(vg::classic_layout(k));
    for (double h : spacings) {
      const auto eyes = grid_nodes(scene, h, vg::classic_layout_walkable_groups());
      for (int th : a.threads) {
        val::ThroughputOptions o;
        o.threads = th;
        o.repeats = a.repeats;
        o.single_rays = a.single;
        o.brute_force = a.brute;
        print_throughput(std::to_string(k) + " " + vg::classic_layout_name(k), h, th,
                         val::measure_throughput(scene, eyes, o));
      }
    }
  }
}

// 1-2. The city, every thread count; its exact all-to-all time on the most.
void city_throughput(const Args& a, const vg::Scene& city, const std::vector<Eigen::Vector3d>& eyes) {
  const int th_max = max_threads(a);
  for (int th : a.threads) {
    val::ThroughputOptions o;
    o.threads = th;
    o.repeats = 1;  // the city is long enough to time once
    o.single_rays = a.single && !a.quick;
    o.brute_force = a.brute;
    const val::Throughput t = val::measure_throughput(city, eyes, o);
    print_throughput("city", 1.0, th, t);
    if (th == th_max)
      std::printf("city all-to-all exact, degree + 4 sigmas, %d thread(s): %.2f s (target <= 10 s on 2 threads)\n", th,
                  t.engine.best_s);
  }
}

// 4. Error against time: S_S for dry snow 4 mm/h (the seed's sigma 0.0374
// 1/m: the largest, so the only one whose pruning radius is inside the
// city), reference = the exact run with that sigma alone.
void pruning_study(const Args& a, const vg::Scene& city, const std::vector<Eigen::Vector3d>& eyes) {
  const int th_max = max_threads(a);
  const double sigma = 0.0374;
  vg::VisibilityOptions exact;
  exact.sigmas = {sigma};
  exact.threads = th_max;
  const vg::VisibilityResult reference = vg::all_to_all(city, eyes, exact);  // also the eps = 0 row
  std::printf("\nerror vs time on the city, S_S for sigma = %.4g 1/m only, %d thread(s), one run each; reference = "
              "exact run (eps 0); bound = certified |S_S error| per node (pruned partners x eps)\n",
              sigma, th_max);
  std::printf("%8s %12s %14s %9s %9s %9s %12s %12s %s\n", "eps", "radius [m]", "pairs cast", "fraction", "time [s]",
              "speed-up", "max|dS_S|", "max bound", "nodes over bound");
  const double exact_seconds = reference.seconds;
  for (double eps : {0.0, 1e-12, 1e-9, 1e-6, 1e-3}) {
    val::PruningPoint p;
    if (eps == 0) {
      p.radius_m = reference.pruning_radius;
      p.pairs_cast = reference.pairs_cast;
      p.seconds = reference.seconds;
    } else {
      p = val::measure_pruning(city, eyes, sigma, eps, reference.sum[0], th_max, 1);
    }
    std::printf("%8.0e %12.4g %14llu %9.4f %9.3f %9.2f %12.3e %12.3e %zu\n", eps, p.radius_m,
                static_cast<unsigned long long>(p.pairs_cast),
                static_cast<double>(p.pairs_cast) / static_cast<double>(reference.pairs_total), p.seconds,
                exact_seconds / p.seconds, p.max_abs_error, p.max_bound, p.bound_violations);
    if (eps == 1e-6)
      std::printf("         (city with eps = 1e-6: %.2f s; target <= 2 s on 2 threads)\n", p.seconds);
  }
}

// 5. The floors.  One line per workload: how the engine decided its pairs,
// where its time went, and its CPU time against both floors.
void print_floors_header() {
  std::printf("\nfloors: the engine (exact, culling on) against raw Embree casting every pair (no scoring) and a raw "
              "vectorised scoring loop (every pair in sight, no rays); CPU seconds of the process, best of the repeats; "
              "the engine's CPU split by phase (cluster classification, packet decisions, scoring, rays) from the "
              "shares measured in one more run with phase timing; ceiling: the most Embree/engine can be when each pair "
              "in sight costs what the scoring loop spends on it and no other pair costs anything; no plane: the "
              "engine without its eyes' plane (which decides sight lines where every node stands at one height)\n");
  std::printf("%-26s %7s %11s %2s %3s %8s %8s %6s %8s %8s %8s %8s %9s %9s %9s %8s %8s %8s %8s %9s %8s %8s\n",
              "workload", "nodes", "pairs", "K", "thr", "sight[%]", "block[%]", "cast%", "cluster", "packets", "score",
              "rays", "engine", "Embree", "scoring", "Embree/", "ceiling", "engine/", "ns/pair", "no plane", "Embree/",
              "cast%");
  std::printf("%-26s %7s %11s %2s %3s %8s %8s %6s %8s %8s %8s %8s %9s %9s %9s %8s %8s %8s %8s %9s %8s %8s\n", "", "", "",
              "", "", "", "", "", "[s]", "[s]", "[s]", "[s]", "cpu [s]", "cpu [s]", "cpu [s]", "engine", "", "scoring",
              "engine", "cpu [s]", "no plane", "no plane");
}

void print_floors(const std::string& name, std::size_t K, int threads, const val::FloorComparison& f) {
  const double percent = 100.0 / static_cast<double>(std::max<std::uint64_t>(f.pairs, 1));
  char rays[32] = "-", over_rays[32] = "-", scoring[32] = "-", over_scoring[32] = "-", ceiling[32] = "-";
  if (f.rays_cpu.best_s > 0) {
    std::snprintf(rays, sizeof rays, "%9.3f", f.rays_cpu.best_s);
    std::snprintf(over_rays, sizeof over_rays, "%8.2f", f.over_rays());
  }
  if (f.scoring_cpu.best_s > 0) {
    std::snprintf(scoring, sizeof scoring, "%9.3f", f.scoring_cpu.best_s);
    std::snprintf(over_scoring, sizeof over_scoring, "%8.2f", f.over_scoring());
  }
  if (f.ceiling() > 0) std::snprintf(ceiling, sizeof ceiling, "%8.2f", f.ceiling());
  char no_plane[32] = "-", over_no_plane[32] = "-", cast_no_plane[32] = "-";
  if (f.engine_no_plane_cpu.best_s > 0) {
    std::snprintf(no_plane, sizeof no_plane, "%9.3f", f.engine_no_plane_cpu.best_s);
    std::snprintf(cast_no_plane, sizeof cast_no_plane, "%8.1f", f.cast_no_plane * percent);
  }
  if (f.over_rays_no_plane() > 0) std::snprintf(over_no_plane, sizeof over_no_plane, "%8.2f", f.over_rays_no_plane());
  std::printf(
      "%-26s %7zu %11llu %2zu %3d %8.1f %8.1f %6.1f %8.3f %8.3f %8.3f %8.3f %9.3f %9s %9s %8s %8s %8s %8.2f %9s %8s %8s\n",
      name.c_str(), f.nodes, static_cast<unsigned long long>(f.pairs), K, threads, f.culled_visible * percent,
      f.culled_blocked * percent, f.cast * percent, f.cluster_s, f.packet_s, f.score_s, f.rays_s, f.engine_cpu.best_s,
      rays, scoring, over_rays, ceiling, over_scoring, 1e9 * f.engine_cpu.best_s * percent / 100, no_plane,
      over_no_plane, cast_no_plane);
  std::fflush(stdout);
}

// `walls`: the scene has some, so the engine is also run without its eyes'
// plane (on the open plane it would be the same engine).
void floors_workload(const Args& a, const std::string& name, const vg::Scene& scene,
                     const std::vector<Eigen::Vector3d>& eyes, const std::vector<double>& sigmas, bool walls = true) {
  val::FloorOptions o;
  o.sigmas = sigmas;
  o.threads = max_threads(a);
  o.repeats = a.repeats;
  o.without_eye_plane = walls;
  print_floors(name, sigmas.size(), o.threads, val::compare_with_floors(scene, eyes, o));
}

void floors_study(const Args& a) {
  print_floors_header();
  const std::vector<double> four = val::seed_benchmark_sigmas(), one = {four.front()};
  {
    vg::Mesh plane;
    plane.vertices = {{0, 0, 0}, {a.plane, 0, 0}, {a.plane, a.plane, 0}, {0, a.plane, 0}};
    plane.triangles = {{0, 1, 2}, {0, 2, 3}};
    plane.triangle_group = {0, 0};
    plane.groups = {"plane"};
    const vg::Scene scene(plane);
    const auto eyes = grid_nodes(scene, 1.0, {});
    const std::string name = "open plane " + std::to_string(static_cast<int>(a.plane)) + " m, 1 m";
    floors_workload(a, name, scene, eyes, one, false);
    floors_workload(a, name, scene, eyes, four, false);
  }
  if (std::filesystem::exists(a.cityjson)) {
    vg::Mesh m = vg::load_cityjson(a.cityjson);
    vg::add_ground_plane(m);
    const vg::Scene scene(m);
    const auto eyes = grid_nodes(scene, a.cityjson_spacing, {});
    char name[64];
    std::snprintf(name, sizeof name, "Delfshaven, %g m", a.cityjson_spacing);
    floors_workload(a, name, scene, eyes, four);
  } else {
    std::printf("%-26s skipped: %s is absent\n", "Delfshaven", a.cityjson.c_str());
  }
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const vg::Scene scene(vg::classic_layout(k));
    floors_workload(a, std::to_string(k) + " " + vg::classic_layout_name(k) + ", 1 m", scene,
                    grid_nodes(scene, 1.0, vg::classic_layout_walkable_groups()), four);
  }
}

int run(const Args& a) {
  const auto start = std::chrono::steady_clock::now();
  print_workload(a);
  if (a.floors_only) {
    floors_study(a);
    return 0;
  }
  memory_study(a);
  layout_throughput(a);
  if (a.floors) floors_study(a);
  if (!a.city) {
    std::printf("\n(city skipped: --no-city)\n");
    return 0;
  }
  vg::CityOptions copt;
  copt.rings = a.city_rings;
  const vg::Scene city(vg::synthetic_city(copt));
  const auto eyes = grid_nodes(city, 1.0, vg::city_walkable_groups());
  std::printf("\ncity: make_city seed %llu, %d rings, %zu triangles, %zu nodes at 1 m on sidewalk+crosswalk\n",
              static_cast<unsigned long long>(copt.seed), copt.rings, city.triangle_count(), eyes.size());
  city_throughput(a, city, eyes);
  if (!a.pruning) return 0;
  pruning_study(a, city, eyes);
  std::printf("\ntotal %.1f s; %s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              val::machine_line().c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "visgraph_throughput: error: %s\n", e.what());
    return 1;
  }
}
