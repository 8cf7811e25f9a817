// Benchmark of the space-syntax measures (visgraph/space_syntax.hpp) against
// their goals, each with the ratio to a plain one-BFS-per-node
// implementation (a queue BFS over adjacency lists, written here, origins
// spread over the same threads) timed in the same run on the same graph.
// Wall and CPU seconds are both printed: on a machine shared with other
// work the wall time overstates what the work needs.
//   layouts   the five classic layouts at 1 m, clear, rain 8 mm/h, heavy
//             advection fog and dry snow 4 mm/h, every local and global
//             measure (goal: <= 2 s in all), at eps = 0.02 and at the
//             report's eps = 0.5;
//   dense     layout 2 at 0.5 m (9,600 nodes, 77 % of pairs in sight), the
//             same measures (goal: <= 10 s);
//   city      the generated city at 1 m (about 50,000 nodes), the same four
//             weathers (goal: <= 10 min);  --city to run it (minutes).
// "Local and global measures" are depthmapX's VGA set: connectivity and
// moments, clustering, control, controllability, mean depth, node count,
// integration [HH]/[P]/[Tekl], entropies, with the weighted connectivity
// and control and the component sizes.  Through vision, the metric
// measures and Onnela's weighted clustering are timed on their own
// (--extras).  The plain BFS computes mean depth only (the cost every global
// measure shares); where it would run for more than ~2e9 edge visits it runs
// from an evenly spaced sample of origins and is scaled up (said so).
//
// Usage: space_syntax_speed [--threads N] [--city] [--city-rings N] [--extras] [--no-dense] [--no-plain]
#include <attenuvis/validation/visgraph_benchmark.hpp>
#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/space_syntax.hpp>
#include <attenuvis/visgraph/visibility.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>
#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>
#include <attenuvis/weather.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace vg = attenuvis::visgraph;
namespace wx = attenuvis::weather;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int tbb_threads(int threads) { return threads > 0 ? threads : tbb::this_task_arena::max_concurrency(); }

// CPU seconds of the whole process (every thread): on a machine shared with
// other work the wall time overstates what the measures need.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The four weathers of the seed's Fig. vg_weather at 550 nm.
std::vector<double> weather_sigmas() {
  std::vector<double> s;
  for (const char* c : {"clear", "rain:8", "fog:advection", "snow:dry:4"})
    s.push_back(wx::sigma(wx::parse_condition(c), 550e-9, wx::Settings{}).per_m);
  return s;
}

vg::MeasureSet classic_measures() {
  return vg::parse_measures("connectivity,clustering,control,controllability,mean-depth,integration,entropy,component");
}

// Adjacency lists of the lines of sight, as a plain implementation holds them.
struct PlainGraph {
  std::vector<std::vector<std::uint32_t>> next;
  std::uint64_t edges = 0;
};

// Mean depth from each origin by one queue BFS each, the origins spread
// over the same threads as the measures; `stride` > 1 runs every stride-th
// origin only.  Returns the wall and CPU seconds and counts the origins
// whose mean depth differs from the library's.
struct PlainTime {
  double wall = 0, cpu = 0;
};
PlainTime plain_bfs(const PlainGraph& g, std::size_t stride, const std::vector<double>& mean_depth, int threads,
                    std::size_t& mismatches) {
  const std::size_t n = g.next.size();
  std::atomic<std::size_t> differ{0};
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  tbb::task_arena arena(tbb_threads(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (n + stride - 1) / stride, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<int> depth(n);
                        std::vector<std::uint32_t> queue(n);
                        for (std::size_t q = r.begin(); q != r.end(); ++q) {
                          const std::size_t s = q * stride;
                          std::fill(depth.begin(), depth.end(), -1);
                          std::size_t head = 0, tail = 0;
                          depth[s] = 0;
                          queue[tail++] = static_cast<std::uint32_t>(s);
                          std::uint64_t total = 0;
                          while (head < tail) {
                            const std::uint32_t v = queue[head++];
                            for (std::uint32_t u : g.next[v])
                              if (depth[u] < 0) depth[u] = depth[v] + 1, total += depth[u], queue[tail++] = u;
                          }
                          const double md = tail > 1 ? static_cast<double>(total) / (tail - 1.0) : -1.0;
                          if (md != mean_depth[s]) ++differ;
                        }
                      });
  });
  mismatches = differ;
  return {seconds_since(t0), cpu_seconds() - cpu0};
}

struct CaseResult {
  double pass = 0, measures = 0, measures_cpu = 0, plain = 0, plain_cpu = 0;
  bool plain_sampled = false;
  std::size_t nodes = 0, mismatches = 0;
  std::uint64_t lines = 0;
  bool bit_rows = true;
};

CaseResult run_case(const vg::Scene& scene, const std::vector<Eigen::Vector3d>& eyes, const std::vector<double>& sigmas,
                    double eps, vg::MeasureSet measures, int threads, double spacing) {
  CaseResult c;
  c.nodes = eyes.size();
  vg::VisibilityOptions pass;
  pass.sigmas = sigmas;
  pass.threads = threads;
  PlainGraph plain;
  plain.next.resize(eyes.size());
  vg::SpaceSyntaxOptions o;
  o.sigmas = sigmas;
  o.contrast_threshold = eps;
  o.measures = measures;
  o.threads = threads;
  o.grid_spacing = spacing;
  const vg::WorkEstimate work = vg::estimate_work(eyes, nullptr, pass);
  vg::GraphCollector collector(eyes, vg::estimate_space_syntax(eyes.size(), work.pairs, o).bit_rows);
  pass.edge_sink = [&](const std::vector<vg::Edge>& block) {
    collector.add(block);
    for (const vg::Edge& e : block) plain.next[e.i].push_back(e.j), plain.next[e.j].push_back(e.i), ++plain.edges;
  };
  const auto t0 = std::chrono::steady_clock::now();
  const vg::VisibilityResult r = vg::all_to_all(scene, eyes, pass);
  c.pass = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  const vg::SpaceSyntaxResult m = vg::space_syntax(collector.finish(), o);
  c.measures = seconds_since(t1);
  c.measures_cpu = cpu_seconds() - cpu0;
  c.lines = r.pairs_visible;
  c.bit_rows = m.bit_rows;
  if (measures.has(vg::Measure::mean_depth) && eps == 0) {
    const double visits = static_cast<double>(eyes.size()) * 2.0 * static_cast<double>(plain.edges);
    const std::size_t stride = visits > 2e9 ? static_cast<std::size_t>(std::ceil(visits / 2e9)) : 1;
    c.plain_sampled = stride > 1;
    const PlainTime t = plain_bfs(plain, stride, m.values("mean_depth", 0), threads, c.mismatches);
    c.plain = t.wall * static_cast<double>(stride);
    c.plain_cpu = t.cpu * static_cast<double>(stride);
  }
  return c;
}

void print(const char* name, const CaseResult& c) {
  std::printf("  %-26s %6zu nodes %10llu lines (%s): pass %7.3f s, measures %8.3f s (%8.3f s CPU)", name,
              c.nodes, static_cast<unsigned long long>(c.lines), c.bit_rows ? "bit rows" : "CSR", c.pass, c.measures,
              c.measures_cpu);
  if (c.plain > 0)
    std::printf(", plain BFS (mean depth, one weather) %8.2f s (%.2f s CPU)%s, mean-depth mismatches %zu", c.plain,
                c.plain_cpu, c.plain_sampled ? " (sampled, scaled)" : "", c.mismatches);
  std::printf("\n");
}

std::vector<Eigen::Vector3d> layout_eyes(const vg::Scene& scene, double spacing) {
  vg::NodeGridOptions o;
  o.spacing = spacing;
  o.walkable = vg::classic_layout_walkable_groups();
  return vg::generate_nodes(scene, o).eyes;
}

// The measures for one weather at eps = 0 (where the plain BFS's graph is the
// same) and for the four weathers at eps.
void layouts(int threads, double eps, bool report_plain) {
  const std::vector<double> sigmas = weather_sigmas();
  double total = 0, total_cpu = 0, plain = 0, plain_cpu = 0, one_weather = 0, one_weather_cpu = 0;
  std::printf("five layouts at 1 m, four weathers, eps = %g:\n", eps);
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const vg::Scene scene(vg::classic_layout(k));
    const std::vector<Eigen::Vector3d> eyes = layout_eyes(scene, 1.0);
    const CaseResult four = run_case(scene, eyes, sigmas, eps, classic_measures(), threads, 1.0);
    print(("layout " + std::to_string(k)).c_str(), four);
    total += four.measures;
    total_cpu += four.measures_cpu;
    if (report_plain) {
      const CaseResult one = run_case(scene, eyes, {0.0}, 0.0, classic_measures(), threads, 1.0);
      plain += one.plain;
      plain_cpu += one.plain_cpu;
      one_weather += one.measures;
      one_weather_cpu += one.measures_cpu;
    }
  }
  std::printf("  => all measures, four weathers: %.3f s wall, %.3f s CPU on %d threads (goal <= 2 s)\n", total,
              total_cpu, tbb_threads(threads));
  if (report_plain)
    std::printf("  => one weather, every measure: %.3f s wall (%.3f s CPU); plain one-BFS-per-node, mean depth alone: "
                "%.2f s wall (%.2f s CPU): ratio %.1f x wall, %.1f x CPU\n",
                one_weather, one_weather_cpu, plain, plain_cpu, plain / one_weather, plain_cpu / one_weather_cpu);
}

void dense(int threads) {
  const vg::Scene scene(vg::classic_layout(2));
  const std::vector<Eigen::Vector3d> eyes = layout_eyes(scene, 0.5);
  std::printf("layout 2 at 0.5 m:\n");
  const CaseResult four = run_case(scene, eyes, weather_sigmas(), vg::kKoschmiederContrast, classic_measures(),
                                   threads, 0.5);
  print("four weathers, eps 0.02", four);
  const CaseResult one = run_case(scene, eyes, {0.0}, 0.0, classic_measures(), threads, 0.5);
  print("clear, eps 0", one);
  std::printf("  => four weathers %.3f s wall, %.3f s CPU (goal <= 10 s); plain one-BFS-per-node %.2f s (%.2f s CPU): "
              "ratio %.1f x wall, %.1f x CPU (one weather each)\n",
              four.measures, four.measures_cpu, one.plain, one.plain_cpu, one.plain / one.measures,
              one.plain_cpu / one.measures_cpu);
}

void city(int threads, int rings) {
  vg::CityOptions co;
  if (rings > 0) co.rings = rings;
  const vg::City c = vg::make_city(co);
  const vg::Scene scene(c.mesh);
  vg::NodeGridOptions no;
  no.spacing = 1.0;
  no.walkable = {"sidewalk", "crosswalk"};
  const std::vector<Eigen::Vector3d> eyes = vg::generate_nodes(scene, no).eyes;
  std::printf("city (%d rings) at 1 m:\n", co.rings);
  const CaseResult four = run_case(scene, eyes, weather_sigmas(), vg::kKoschmiederContrast, classic_measures(),
                                   threads, 1.0);
  print("four weathers, eps 0.02", four);
  const CaseResult one = run_case(scene, eyes, {0.0}, 0.0, classic_measures(), threads, 1.0);
  print("clear, eps 0", one);
  std::printf("  => four weathers %.1f s wall (%.1f s CPU) + pass %.1f s (goal <= 600 s); plain one-BFS-per-node %.0f s "
              "(%.0f s CPU): ratio %.1f x wall, %.1f x CPU (one weather each)\n",
              four.measures, four.measures_cpu, four.pass, one.plain, one.plain_cpu, one.plain / one.measures,
              one.plain_cpu / one.measures_cpu);
}

void extras(int threads) {
  std::printf("the other measures, layout 2 at 1 m, four weathers, eps 0.5 (one at a time):\n");
  const vg::Scene scene(vg::classic_layout(2));
  const std::vector<Eigen::Vector3d> eyes = layout_eyes(scene, 1.0);
  for (const char* m : {"through-vision", "metric", "clustering-weighted"}) {
    const CaseResult c = run_case(scene, eyes, weather_sigmas(), 0.5, vg::parse_measures(m), threads, 1.0);
    print(m, c);
  }
}
}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each line as it comes (the city takes minutes)
  int threads = 0, rings = 0;
  bool with_city = false, with_extras = false, with_dense = true, with_plain = true;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--threads" && a + 1 < argc) threads = std::stoi(argv[++a]);
    else if (s == "--city") with_city = true;
    else if (s == "--city-rings" && a + 1 < argc) rings = std::stoi(argv[++a]), with_city = true;
    else if (s == "--extras") with_extras = true;
    else if (s == "--no-dense") with_dense = false;
    else if (s == "--no-plain") with_plain = false;
    else {
      std::fprintf(stderr, "usage: space_syntax_speed [--threads N] [--city] [--city-rings N] [--extras] [--no-dense] [--no-plain]\n");
      return 2;
    }
  }
  try {
    layouts(threads, vg::kKoschmiederContrast, with_plain);
    layouts(threads, 0.5, false);
    if (with_dense) dense(threads);
    if (with_extras) extras(threads);
    if (with_city) city(threads, rings);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "space_syntax_speed: %s\n", e.what());
    return 1;
  }
  return 0;
}
