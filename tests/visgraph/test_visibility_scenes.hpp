// Small scenes built inline for the visgraph tests, and an independent
// brute-force line-of-sight evaluation (double precision, no Embree).
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vgtest {

using attenuvis::visgraph::Mesh;
using Eigen::Vector3d;

inline void add_triangle(Mesh& m, const Vector3d& a, const Vector3d& b, const Vector3d& c, const std::string& group) {
  const auto g = static_cast<std::uint32_t>(m.add_group(group));
  const auto base = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back(a);
  m.vertices.push_back(b);
  m.vertices.push_back(c);
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangle_group.push_back(g);
}

inline void add_quad(Mesh& m, const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d,
                     const std::string& group) {
  add_triangle(m, a, b, c, group);
  add_triangle(m, a, c, d, group);
}

// Horizontal rectangle [x0,x1] x [y0,y1] at height z.
inline void add_floor(Mesh& m, double x0, double x1, double y0, double y1, double z, const std::string& group) {
  add_quad(m, {x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, group);
}

// Closed axis-aligned box (12 triangles).
inline void add_box(Mesh& m, const Vector3d& lo, const Vector3d& hi, const std::string& group) {
  const auto P = [&](int x, int y, int z) { return Vector3d(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z()); };
  add_quad(m, P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0), group);
  add_quad(m, P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1), group);
  add_quad(m, P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1), group);
  add_quad(m, P(0, 1, 0), P(1, 1, 0), P(1, 1, 1), P(0, 1, 1), group);
  add_quad(m, P(0, 0, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1), group);
  add_quad(m, P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1), group);
}

// Grid of eye points at cell centres of [x0,x1] x [y0,y1], pitch h, height z.
inline std::vector<Vector3d> grid_points(double x0, double x1, double y0, double y1, double h, double z) {
  std::vector<Vector3d> p;
  for (double y = y0 + h / 2; y < y1; y += h)
    for (double x = x0 + h / 2; x < x1; x += h) p.emplace_back(x, y, z);
  return p;
}

// Möller–Trumbore in double: does the segment a + t (b - a), t in [t0, t1],
// meet triangle (p, q, r)?  A segment parallel to the triangle's plane
// (det = 0) does not meet it (grazing contact is not occlusion).
inline bool segment_hits_triangle(const Vector3d& a, const Vector3d& b, double t0, double t1, const Vector3d& p,
                                  const Vector3d& q, const Vector3d& r) {
  const Vector3d d = b - a, e1 = q - p, e2 = r - p;
  const Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (det == 0) return false;
  const double inv = 1.0 / det;
  const Vector3d s = a - p;
  const double u = inv * s.dot(h);
  if (u < 0 || u > 1) return false;
  const Vector3d qv = s.cross(e1);
  const double v = inv * d.dot(qv);
  if (v < 0 || u + v > 1) return false;
  const double t = inv * e2.dot(qv);
  return t >= t0 && t <= t1;
}

// The library's documented policy: segment shortened by 1e-4 m + 1e-6 d at
// both ends; pairs closer than 1e-6 m are not lines of sight.
inline bool brute_force_visible(const Mesh& m, const Vector3d& a, const Vector3d& b) {
  const double d = (b - a).norm();
  if (d < 1e-6) return false;
  const double gap = 1e-4 + 1e-6 * d;
  if (d <= 2 * gap) return true;
  for (const auto& t : m.triangles)
    if (segment_hits_triangle(a, b, gap / d, 1 - gap / d, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]))
      return false;
  return true;
}

struct BruteForce {
  std::vector<std::uint32_t> degree;
  std::vector<std::vector<long double>> sum;  // [k][i]
};

inline BruteForce brute_force_all_pairs(const Mesh& m, const std::vector<Vector3d>& nodes,
                                        const std::vector<double>& sigmas) {
  BruteForce bf;
  bf.degree.assign(nodes.size(), 0);
  bf.sum.assign(sigmas.size(), std::vector<long double>(nodes.size(), 0.0L));
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      if (!brute_force_visible(m, nodes[i], nodes[j])) continue;
      ++bf.degree[i];
      ++bf.degree[j];
      const long double d = (nodes[j] - nodes[i]).norm();
      for (std::size_t k = 0; k < sigmas.size(); ++k) {
        const long double c = std::exp(-static_cast<long double>(sigmas[k]) * d);
        bf.sum[k][i] += c;
        bf.sum[k][j] += c;
      }
    }
  return bf;
}

}  // namespace vgtest
