// Local-frame node arrays (node_points.hpp).
#include "node_points.hpp"

#include <attenuvis/visgraph/limits.hpp>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph::detail {

Points to_local(const Scene& scene, const std::vector<Eigen::Vector3d>& world, const char* what) {
  Points p;
  p.x.reserve(world.size());
  p.y.reserve(world.size());
  p.z.reserve(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) {
    if (!world[i].allFinite())
      throw std::invalid_argument(std::string(what) + " " + std::to_string(i + 1) + " has a non-finite coordinate");
    for (int c = 0; c < 3; ++c) check_coordinate(world[i][c], std::string(what) + " " + std::to_string(i + 1));
    const Eigen::Vector3d l = scene.to_local(world[i]);
    p.x.push_back(l.x());
    p.y.push_back(l.y());
    p.z.push_back(l.z());
  }
  return p;
}

Points sorted_by_x(const Points& p, std::vector<std::uint32_t>& order) {
  order.resize(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (p.x[a] != p.x[b]) return p.x[a] < p.x[b];
    if (p.y[a] != p.y[b]) return p.y[a] < p.y[b];
    if (p.z[a] != p.z[b]) return p.z[a] < p.z[b];
    return a < b;
  });
  Points s;
  for (std::uint32_t i : order) {
    s.x.push_back(p.x[i]);
    s.y.push_back(p.y[i]);
    s.z.push_back(p.z[i]);
  }
  return s;
}

double pairs_within_x(const Points& sources, const Points& partners, bool symmetric, double radius) {
  std::vector<double> s = sources.x, t = symmetric ? std::vector<double>() : partners.x;
  std::sort(s.begin(), s.end());
  std::sort(t.begin(), t.end());
  return pairs_within_sorted_x(s, symmetric ? nullptr : &t, radius);
}

double pairs_within_sorted_x(const std::vector<double>& sources_x, const std::vector<double>* partners_x,
                             double radius) {
  const std::vector<double>& s = sources_x;
  const std::vector<double>& p = partners_x ? *partners_x : s;
  double count = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto hi = std::upper_bound(p.begin(), p.end(), s[i] + radius);
    const auto lo = partners_x ? std::lower_bound(p.begin(), p.end(), s[i] - radius)
                               : p.begin() + static_cast<std::ptrdiff_t>(i + 1);
    if (hi > lo) count += static_cast<double>(hi - lo);
  }
  return count;
}

}  // namespace attenuvis::visgraph::detail
