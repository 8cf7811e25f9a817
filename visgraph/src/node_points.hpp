// Nodes in the scene's local frame as the visibility passes use them: three
// coordinate arrays (a nanoflann point cloud), made from world points with
// their range checked, and sorted by x.  Internal to the visgraph library.
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

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

// World points to the local frame; throws naming `what` and the 1-based
// index of a non-finite or out-of-range coordinate.
Points to_local(const Scene& scene, const std::vector<Eigen::Vector3d>& world, const char* what);

// The points in increasing x (ties by y, z, index: deterministic);
// order[s] = original index of sorted point s.
Points sorted_by_x(const Points& p, std::vector<std::uint32_t>& order);

// Pairs whose x coordinates lie within `radius` of each other (an upper
// bound on the pairs a pruned pass casts), O((N + M) log(N + M)).
double pairs_within_x(const Points& sources, const Points& partners, bool symmetric, double radius);
// The same from x coordinates sorted increasing; partners_x null: every
// unordered pair of the sources.
double pairs_within_sorted_x(const std::vector<double>& sources_x, const std::vector<double>* partners_x,
                             double radius);

// Pruning is chosen over the exact pass only when at most this fraction of
// the pairs lie within its radius along x (visibility.hpp, "Pruning"): a
// pruned pass casts every pair within the radius, the exact pass culls.
constexpr double kPruneWorthFraction = 0.1;
inline bool pruning_pays(double pairs_within_x, double pairs_total) {
  return !(pairs_within_x > kPruneWorthFraction * pairs_total);
}

}  // namespace attenuvis::visgraph::detail
