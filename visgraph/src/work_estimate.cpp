// Work and memory of a visibility pass before it runs (work_estimate.hpp).
#include <attenuvis/visgraph/work_estimate.hpp>

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

double o_max_distance(const VisibilityOptions& o) { return o.max_distance; }

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
    if (!std::isfinite(radius)) return all;
    const std::vector<double>& partners = targets ? t : s;
    double pairs = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto hi = std::upper_bound(partners.begin(), partners.end(), s[i] + radius);
      const auto lo = targets ? std::lower_bound(partners.begin(), partners.end(), s[i] - radius)
                              : partners.begin() + static_cast<std::ptrdiff_t>(i + 1);
      if (hi > lo) pairs += static_cast<double>(hi - lo);
    }
    return pairs;
  };
  e.pairs = slab_pairs(e.radius);
  // The pass runs exact instead of pruning when more than a tenth of the
  // pairs lie within the pruning radius (visibility.hpp): count its pairs.
  const bool pruning = e.radius < o_max_distance(options);
  if (pruning && !options.always_prune && e.pairs > 0.1 * all) {
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
