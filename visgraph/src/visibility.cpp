// All-pairs and source-to-target visibility with contrast-ratio scores.
//
// One row per source node: its partners (all j > i, or a kd-tree radius
// search when pruning) are cast 16 at a time with rtcOccluded16, all rays of a
// packet sharing the row's origin (coherent traversal).  The packet's
// distances go through the vectorised contrast kernel and the fixed-point
// results are added to the row (and, all-to-all, to the partners) in
// per-thread integer accumulators reduced at the end: exact, so independent
// of thread count and schedule.
#include <attenuvis/visgraph/visibility.hpp>

#include "contrast_kernel.hpp"
#include "progress.hpp"

#include <embree3/rtcore.h>
#include <nanoflann.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

namespace {
using detail::kContrastScale;
using detail::kDistanceScale;
using detail::kLanes;

constexpr double kCoincident = 1e-6;  // m
inline double end_gap(double d) { return 1e-4 + 1e-6 * d; }

struct Points {
  std::vector<double> x, y, z;  // local (recentred) frame, double
  std::size_t size() const { return x.size(); }
  std::size_t kdtree_get_point_count() const { return x.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return dim == 0 ? x[i] : dim == 1 ? y[i] : z[i]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, std::uint32_t>;

Points to_local(const Scene& scene, const std::vector<Eigen::Vector3d>& world, const char* what) {
  Points p;
  p.x.reserve(world.size());
  p.y.reserve(world.size());
  p.z.reserve(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) {
    if (!world[i].allFinite())
      throw std::invalid_argument(std::string(what) + " " + std::to_string(i + 1) + " has a non-finite coordinate");
    const Eigen::Vector3d l = scene.to_local(world[i]);
    p.x.push_back(l.x());
    p.y.push_back(l.y());
    p.z.push_back(l.z());
  }
  return p;
}

void validate(const VisibilityOptions& o) {
  for (double s : o.sigmas)
    if (!std::isfinite(s) || s < 0) throw std::invalid_argument("visibility: sigma must be finite and >= 0 (1/m)");
  if (!(o.tolerance >= 0) || !(o.tolerance < 1)) throw std::invalid_argument("visibility: tolerance must be in [0, 1)");
  if (!(o.max_distance > 0)) throw std::invalid_argument("visibility: max distance must be positive");
  if (o.threads < 0) throw std::invalid_argument("visibility: thread count must be >= 0");
}

// Accumulator slots per node: degree, distance sum, then one per sigma.
struct ThreadState {
  std::vector<std::int64_t> acc;
  std::vector<double> max_distance;
  std::vector<std::uint32_t> candidates;
  std::vector<std::pair<std::uint32_t, double>> matches;
  std::vector<std::int64_t> c_fixed;
  std::uint64_t cast = 0, visible = 0, coincident = 0;
};

struct Pass {
  const Scene* scene = nullptr;
  RTCScene rtc = nullptr;
  const Points* sources = nullptr;
  const Points* partners = nullptr;
  bool symmetric = false;  // all-to-all: credit partners too
  std::size_t stride = 0;
  int K = 0;
  std::vector<double> neg_sigma;
  double max_distance = 0;
  bool keep_max = false;
};

// Casts row i against `count` partners and accumulates.
void process_row(const Pass& pass, std::size_t i, const std::uint32_t* cand, std::size_t count, ThreadState& ts,
                 std::vector<Edge>* edges) {
  const Points& S = *pass.sources;
  const Points& P = *pass.partners;
  const double ox = S.x[i], oy = S.y[i], oz = S.z[i];
  const int K = pass.K;
  std::int64_t* row = ts.acc.data() + i * pass.stride;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRay16 ray;
  alignas(64) int valid[kLanes];
  alignas(64) double dist[kLanes], vis[kLanes];
  alignas(64) std::int64_t d_fixed[kLanes];
  std::uint32_t partner[kLanes];
  for (std::size_t start = 0; start < count; start += kLanes) {
    const int n = static_cast<int>(std::min<std::size_t>(kLanes, count - start));
    bool any = false;
    for (int l = 0; l < kLanes; ++l) {
      valid[l] = 0;
      vis[l] = 0;
      dist[l] = 0;
      if (l >= n) continue;
      const std::uint32_t j = cand[start + l];
      partner[l] = j;
      const double dx = P.x[j] - ox, dy = P.y[j] - oy, dz = P.z[j] - oz;
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (d < kCoincident) {
        ++ts.coincident;
        continue;
      }
      if (d > pass.max_distance) continue;
      dist[l] = d;
      const double gap = end_gap(d);
      if (d <= 2 * gap) {  // no room for geometry: visible without a ray
        vis[l] = 1;
        continue;
      }
      valid[l] = -1;
      any = true;
      ray.org_x[l] = static_cast<float>(ox);
      ray.org_y[l] = static_cast<float>(oy);
      ray.org_z[l] = static_cast<float>(oz);
      ray.dir_x[l] = static_cast<float>(dx);
      ray.dir_y[l] = static_cast<float>(dy);
      ray.dir_z[l] = static_cast<float>(dz);
      ray.tnear[l] = static_cast<float>(gap / d);
      ray.tfar[l] = static_cast<float>(1.0 - gap / d);
      ray.time[l] = 0;
      ray.mask[l] = 0xFFFFFFFFu;
      ray.id[l] = 0;
      ray.flags[l] = 0;
    }
    if (any) {
      rtcOccluded16(valid, pass.rtc, &context, &ray);
      for (int l = 0; l < n; ++l)
        if (valid[l]) {
          ++ts.cast;
          vis[l] = ray.tfar[l] >= 0 ? 1.0 : 0.0;  // Embree sets tfar = -inf when occluded
        }
    }
    std::int64_t* c = ts.c_fixed.data();
    detail::contrast_lanes(dist, vis, pass.neg_sigma.data(), K, c, d_fixed);
    for (int l = 0; l < n; ++l) {
      if (vis[l] == 0) continue;
      ++ts.visible;
      const std::uint32_t j = partner[l];
      row[0] += 1;
      row[1] += d_fixed[l];
      for (int k = 0; k < K; ++k) row[2 + k] += c[k * kLanes + l];
      if (pass.keep_max) ts.max_distance[i] = std::max(ts.max_distance[i], dist[l]);
      if (pass.symmetric) {
        std::int64_t* other = ts.acc.data() + j * pass.stride;
        other[0] += 1;
        other[1] += d_fixed[l];
        for (int k = 0; k < K; ++k) other[2 + k] += c[k * kLanes + l];
        if (pass.keep_max) ts.max_distance[j] = std::max(ts.max_distance[j], dist[l]);
      }
      if (edges) edges->push_back(Edge{static_cast<std::uint32_t>(i), j, dist[l]});
    }
  }
}

VisibilityResult run_pass(const Scene& scene, const Points& sources, const Points& partners, bool symmetric,
                          const VisibilityOptions& options) {
  validate(options);
  if (sources.size() == 0) throw std::invalid_argument("visibility: no nodes");
  if (!symmetric && partners.size() == 0) throw std::invalid_argument("visibility: no targets");
  if (sources.size() > 0xFFFFFFFFu || partners.size() > 0xFFFFFFFFu)
    throw std::invalid_argument("visibility: more than 2^32 nodes");
  const auto start_time = std::chrono::steady_clock::now();

  VisibilityResult result;
  const std::size_t N = sources.size(), M = partners.size();
  result.nodes = N;
  result.tolerance = options.tolerance;
  const int K = static_cast<int>(options.sigmas.size());

  // Pruning radius R = ln(1/eps)/sigma_min (infinite without pruning).
  double sigma_min = std::numeric_limits<double>::infinity();
  for (double s : options.sigmas) sigma_min = std::min(sigma_min, s);
  double prune_radius = std::numeric_limits<double>::infinity();
  if (options.tolerance > 0 && K > 0 && sigma_min > 0) prune_radius = std::log(1.0 / options.tolerance) / sigma_min;
  const double radius = std::min(prune_radius, options.max_distance);
  const bool pruning = prune_radius < options.max_distance;
  result.pruning_radius = prune_radius;
  result.degree_exact = !pruning;

  Pass pass;
  pass.scene = &scene;
  pass.rtc = static_cast<RTCScene>(scene.embree_scene());
  pass.sources = &sources;
  pass.partners = &partners;
  pass.symmetric = symmetric;
  pass.K = K;
  pass.stride = 2 + static_cast<std::size_t>(K);
  for (double s : options.sigmas) pass.neg_sigma.push_back(-s);
  pass.max_distance = options.max_distance;
  pass.keep_max = options.distance_stats;

  std::unique_ptr<KdTree> tree;
  if (std::isfinite(radius)) tree = std::make_unique<KdTree>(3, partners, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  // nanoflann keeps points with squared distance < radius^2 (strict); widen a
  // little and let process_row apply "d <= max_distance" exactly.
  const double radius_sq = radius * radius * (1 + 1e-9) + 1e-12;

  tbb::enumerable_thread_specific<ThreadState> states([&] {
    ThreadState ts;
    ts.acc.assign(N * pass.stride, 0);
    if (pass.keep_max) ts.max_distance.assign(N, 0.0);
    ts.c_fixed.assign(static_cast<std::size_t>(std::max(K, 1)) * kLanes, 0);
    return ts;
  });
  std::vector<std::uint32_t> pruned(N, 0);
  result.pairs_total = symmetric ? static_cast<std::uint64_t>(N) * (N - 1) / 2 : static_cast<std::uint64_t>(N) * M;

  // Edge output goes block by block, in row order, so the list never sits
  // whole in memory.
  const std::size_t block_rows =
      options.edge_sink ? std::max<std::size_t>(1, (std::size_t{1} << 22) / std::max<std::size_t>(M, 1)) : N;
  std::vector<std::vector<Edge>> row_edges(options.edge_sink ? block_rows : 0);

  Progress progress(options.progress, result.pairs_total, "vg");
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    for (std::size_t block = 0; block < N; block += block_rows) {
      const std::size_t block_end = std::min(N, block + block_rows);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(block, block_end, 1),
                        [&](const tbb::blocked_range<std::size_t>& range) {
        ThreadState& ts = states.local();
        std::uint64_t done = 0;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          ts.candidates.clear();
          const std::size_t first = symmetric ? i + 1 : 0;
          if (tree) {
            const double q[3] = {sources.x[i], sources.y[i], sources.z[i]};
            ts.matches.clear();
            tree->radiusSearch(q, radius_sq, ts.matches, nanoflann::SearchParams(32, 0, false));
            std::size_t within = 0;
            for (const auto& m : ts.matches) {
              if (symmetric && m.first == i) continue;
              ++within;
              if (m.first >= first) ts.candidates.push_back(m.first);
            }
            std::sort(ts.candidates.begin(), ts.candidates.end());
            if (pruning) pruned[i] = static_cast<std::uint32_t>((symmetric ? N - 1 : M) - within);
          } else {
            for (std::size_t j = first; j < M; ++j) ts.candidates.push_back(static_cast<std::uint32_t>(j));
          }
          std::vector<Edge>* edges = options.edge_sink ? &row_edges[i - block] : nullptr;
          if (edges) edges->clear();
          process_row(pass, i, ts.candidates.data(), ts.candidates.size(), ts, edges);
          done += symmetric ? N - 1 - i : M;
        }
        progress.add(done);
      });
      if (options.edge_sink) {
        std::vector<Edge> out;
        for (std::size_t i = block; i < block_end; ++i) out.insert(out.end(), row_edges[i - block].begin(), row_edges[i - block].end());
        options.edge_sink(out);
      }
    }
  });
  progress.finish();

  // Exact reduction of the per-thread integer accumulators.
  std::vector<std::int64_t> total(N * pass.stride, 0);
  std::vector<double> max_distance(pass.keep_max ? N : 0, 0.0);
  for (const ThreadState& ts : states) {
    for (std::size_t s = 0; s < total.size(); ++s) total[s] += ts.acc[s];
    for (std::size_t i = 0; i < max_distance.size(); ++i) max_distance[i] = std::max(max_distance[i], ts.max_distance[i]);
    result.pairs_cast += ts.cast;
    result.pairs_visible += ts.visible;
    result.coincident_pairs += ts.coincident;
  }
  result.sum.assign(static_cast<std::size_t>(K), std::vector<double>(N));
  for (std::size_t i = 0; i < N; ++i)
    for (int k = 0; k < K; ++k)
      result.sum[static_cast<std::size_t>(k)][i] = static_cast<double>(total[i * pass.stride + 2 + k]) / kContrastScale;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (result.degree_exact) {
    result.degree.resize(N);
    for (std::size_t i = 0; i < N; ++i) result.degree[i] = static_cast<std::uint32_t>(total[i * pass.stride]);
    if (options.distance_stats) {
      result.mean_distance.resize(N);
      result.max_distance.resize(N);
      for (std::size_t i = 0; i < N; ++i) {
        const std::int64_t deg = total[i * pass.stride];
        result.mean_distance[i] = deg ? static_cast<double>(total[i * pass.stride + 1]) / kDistanceScale / deg : nan;
        result.max_distance[i] = deg ? max_distance[i] : nan;
      }
    }
  }
  result.pruned = std::move(pruned);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}
}  // namespace

double VisibilityResult::average(std::size_t k, std::size_t i) const {
  if (degree.empty() || degree[i] == 0) return std::numeric_limits<double>::quiet_NaN();
  return sum[k][i] / degree[i];
}

VisibilityResult all_to_all(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                            const VisibilityOptions& options) {
  const Points points = to_local(scene, eyes, "node");
  return run_pass(scene, points, points, true, options);
}

VisibilityResult to_targets(const Scene& scene, const std::vector<Eigen::Vector3d>& sources,
                            const std::vector<Eigen::Vector3d>& targets, const VisibilityOptions& options) {
  const Points s = to_local(scene, sources, "node");
  const Points t = to_local(scene, targets, "target");
  return run_pass(scene, s, t, false, options);
}

std::uint64_t raw_visible_pairs(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes, int threads,
                                RawMethod method) {
  const Points P = to_local(scene, eyes, "node");
  const RTCScene rtc = static_cast<RTCScene>(scene.embree_scene());
  const std::size_t N = P.size();
  std::atomic<std::uint64_t> visible{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 1), [&](const tbb::blocked_range<std::size_t>& range) {
      std::uint64_t seen = 0;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      if (method == RawMethod::packets16) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const double ox = P.x[i], oy = P.y[i], oz = P.z[i];
        if (method == RawMethod::single_rays) {
          for (std::size_t j = i + 1; j < N; ++j) {
            const double dx = P.x[j] - ox, dy = P.y[j] - oy, dz = P.z[j] - oz;
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (d < kCoincident) continue;
            const double gap = end_gap(d);
            RTCRay ray{};
            ray.org_x = static_cast<float>(ox);
            ray.org_y = static_cast<float>(oy);
            ray.org_z = static_cast<float>(oz);
            ray.dir_x = static_cast<float>(dx);
            ray.dir_y = static_cast<float>(dy);
            ray.dir_z = static_cast<float>(dz);
            ray.tnear = static_cast<float>(gap / d);
            ray.tfar = static_cast<float>(1.0 - gap / d);
            ray.mask = 0xFFFFFFFFu;
            rtcOccluded1(rtc, &context, &ray);
            seen += ray.tfar >= 0;
          }
          continue;
        }
        RTCRay16 ray;
        alignas(64) int valid[kLanes];
        for (std::size_t start = i + 1; start < N; start += kLanes) {
          for (int l = 0; l < kLanes; ++l) {
            const std::size_t j = start + static_cast<std::size_t>(l);
            valid[l] = 0;
            if (j >= N) continue;
            const double dx = P.x[j] - ox, dy = P.y[j] - oy, dz = P.z[j] - oz;
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (d < kCoincident) continue;
            const double gap = end_gap(d);
            valid[l] = -1;
            ray.org_x[l] = static_cast<float>(ox);
            ray.org_y[l] = static_cast<float>(oy);
            ray.org_z[l] = static_cast<float>(oz);
            ray.dir_x[l] = static_cast<float>(dx);
            ray.dir_y[l] = static_cast<float>(dy);
            ray.dir_z[l] = static_cast<float>(dz);
            ray.tnear[l] = static_cast<float>(gap / d);
            ray.tfar[l] = static_cast<float>(1.0 - gap / d);
            ray.time[l] = 0;
            ray.mask[l] = 0xFFFFFFFFu;
            ray.id[l] = 0;
            ray.flags[l] = 0;
          }
          rtcOccluded16(valid, rtc, &context, &ray);
          for (int l = 0; l < kLanes; ++l) seen += valid[l] && ray.tfar[l] >= 0;
        }
      }
      visible += seen;
    });
  });
  return visible.load();
}

}  // namespace attenuvis::visgraph
