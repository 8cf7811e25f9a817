// Work and memory of a visibility pass before it runs (work_estimate.hpp).
#include <attenuvis/visgraph/work_estimate.hpp>

#include "node_points.hpp"

#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <unistd.h>

namespace attenuvis::visgraph {

namespace {
// The radius visibility.cpp's plan_pass uses: the pruning radius
// ln(1/eps)/sigma_min when pruning applies, capped by max_distance.
double candidate_radius(const VisibilityOptions& o) {
  return std::min(pruning_radius(o.prune_below, o.sigmas), o.max_distance);
}

std::vector<double> sorted_x(const std::vector<Eigen::Vector3d>& p) {
  std::vector<double> x;
  x.reserve(p.size());
  for (const Eigen::Vector3d& v : p) x.push_back(v.x());
  std::sort(x.begin(), x.end());
  return x;
}
}  // namespace

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

WorkEstimate estimate_work(const std::vector<Eigen::Vector3d>& sources, const std::vector<Eigen::Vector3d>* targets,
                           const VisibilityOptions& options) {
  WorkEstimate e;
  e.nodes = sources.size();
  e.targets = targets ? targets->size() : 0;
  e.radius = candidate_radius(options);
  e.threads = options.threads > 0 ? options.threads : std::max(1, tbb::info::default_concurrency());
  const double N = static_cast<double>(e.nodes), M = static_cast<double>(e.targets);
  const double all = targets ? N * M : N * (N - 1) / 2;
  // The pass's candidates lie within the radius in x (a slab): count those.
  const std::vector<double> s = sorted_x(sources);
  const std::vector<double> t = targets ? sorted_x(*targets) : std::vector<double>();
  const auto slab_pairs = [&](double radius) {
    return std::isfinite(radius) ? detail::pairs_within_sorted_x(s, targets ? &t : nullptr, radius) : all;
  };
  e.pairs = slab_pairs(e.radius);
  // The pass runs exact instead of pruning where pruning does not pay
  // (visibility.hpp): count its pairs.
  const bool pruning = e.radius < options.max_distance;
  if (pruning && !options.always_prune && !detail::pruning_pays(e.pairs, all)) {
    e.radius = options.max_distance;
    e.pairs = slab_pairs(e.radius);
  }
  // Per thread: slot-major int64 accumulators (degree, distance, one per
  // sigma, within-radius count) and max distances, for every source node.
  const double slots = 4.0 + static_cast<double>(options.sigmas.size());
  e.bytes = e.threads * N * (slots + (options.distance_stats ? 1 : 0)) * 8.0 + (N + M) * 2 * 24.0 +
            N * (options.sigmas.size() + 4) * 8.0;  // points, sorted copy, results
  return e;
}

}  // namespace attenuvis::visgraph
