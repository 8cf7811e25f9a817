// Ear clipping of a planar polygon with holes.
//
// No Debian package attenuvis may use triangulates polygons with holes
// (tinyobjloader only fans or clips hole-free n-gons), so this file does it:
// the classic method (Eberly, "Triangulation by Ear Clipping", Geometric
// Tools 2002): holes are joined to the outline by a bridge from their
// rightmost vertex to the nearest outline vertex it can see, then ears are
// clipped one at a time.  O(n^2) per polygon, which suits the tens of
// vertices of a building face.
#include <attenuvis/visgraph/detail/polygon.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace attenuvis::visgraph {

namespace {

using Vec2 = Eigen::Vector2d;

struct Corner {
  std::uint32_t index;  // into the concatenated rings
  Vec2 p;               // in the polygon's plane
};
using Ring = std::vector<Corner>;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double signed_area(const Ring& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) a += cross(Vec2::Zero(), r[i].p, r[(i + 1) % r.size()].p);
  return 0.5 * a;
}

// Newell's normal of a ring (robust for concave and slightly non-planar rings).
Eigen::Vector3d newell_normal(const std::vector<Eigen::Vector3d>& ring) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector3d& a = ring[i];
    const Eigen::Vector3d& b = ring[(i + 1) % ring.size()];
    n.x() += (a.y() - b.y()) * (a.z() + b.z());
    n.y() += (a.z() - b.z()) * (a.x() + b.x());
    n.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return n;
}

// Drops consecutive repeats (and a closing repeat of the first vertex).
std::vector<std::uint32_t> distinct_corners(const std::vector<Eigen::Vector3d>& ring, std::uint32_t first,
                                            double tolerance) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (!out.empty() && (ring[i] - ring[out.back() - first]).norm() <= tolerance) continue;
    out.push_back(first + static_cast<std::uint32_t>(i));
  }
  while (out.size() > 1 && (ring[out.back() - first] - ring[out.front() - first]).norm() <= tolerance) out.pop_back();
  return out;
}

// Removes corners that lie on the line through their neighbours (they add
// no area and would only make slivers), until none is left.
void drop_collinear(Ring& r, double area_tolerance) {
  bool changed = true;
  while (changed && r.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < r.size() && r.size() >= 3; ++i) {
      const std::size_t n = r.size();
      if (std::abs(cross(r[(i + n - 1) % n].p, r[i].p, r[(i + 1) % n].p)) <= area_tolerance) {
        r.erase(r.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
    }
  }
}

// True if the open segments ab and cd cross (touching at an end does not count).
bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool crosses_any(const Vec2& a, const Vec2& b, const Ring& ring) {
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (segments_cross(a, b, ring[i].p, ring[(i + 1) % ring.size()].p)) return true;
  return false;
}

// Joins `hole` (clockwise) into `outline` (counter-clockwise) by a bridge
// from the hole's rightmost corner to the nearest outline corner it sees
// without crossing the outline, the hole or any hole still to be joined.
bool bridge(Ring& outline, const Ring& hole, const std::vector<Ring>& others) {
  std::size_t m = 0;
  for (std::size_t i = 1; i < hole.size(); ++i)
    if (hole[i].p.x() > hole[m].p.x()) m = i;
  const Vec2 M = hole[m].p;
  std::size_t best = outline.size();
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const double d = (outline[i].p - M).squaredNorm();
    if (d >= best_d) continue;
    const Vec2& P = outline[i].p;
    if (crosses_any(M, P, outline) || crosses_any(M, P, hole)) continue;
    bool blocked = false;
    for (const Ring& o : others) blocked = blocked || crosses_any(M, P, o);
    if (blocked) continue;
    best = i;
    best_d = d;
  }
  if (best == outline.size()) return false;
  Ring merged(outline.begin(), outline.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  for (std::size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(m + k) % hole.size()]);
  merged.insert(merged.end(), outline.begin() + static_cast<std::ptrdiff_t>(best), outline.end());
  outline = std::move(merged);
  return true;
}

bool inside_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

// Clips ears off a counter-clockwise polygon; false if it gets stuck.
bool clip_ears(Ring poly, double area_tolerance, std::vector<std::array<std::uint32_t, 3>>& out) {
  std::size_t stuck = 0;
  std::size_t i = 0;
  while (poly.size() > 3 && stuck < poly.size()) {
    const std::size_t n = poly.size();
    const Corner& a = poly[(i + n - 1) % n];
    const Corner& v = poly[i % n];
    const Corner& b = poly[(i + 1) % n];
    const double c = cross(a.p, v.p, b.p);
    bool clip = false, emit = false;
    if (std::abs(c) <= area_tolerance) {
      clip = true;  // collinear or repeated corner: drop it, no triangle
    } else if (c > 0) {
      clip = emit = true;
      for (std::size_t k = 0; k < n && clip; ++k) {
        const Vec2& p = poly[k].p;
        if (p == a.p || p == v.p || p == b.p) continue;
        if (inside_triangle(p, a.p, v.p, b.p)) clip = false;
      }
    }
    if (clip) {
      if (emit) out.push_back({a.index, v.index, b.index});
      poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(i % n));
      stuck = 0;
      if (i > 0) --i;
    } else {
      ++stuck;
      i = (i + 1) % n;
    }
  }
  if (poly.size() == 3) {
    if (cross(poly[0].p, poly[1].p, poly[2].p) > area_tolerance) out.push_back({poly[0].index, poly[1].index, poly[2].index});
    return true;
  }
  return poly.size() < 3;
}

}  // namespace

PolygonTriangles triangulate_polygon(const std::vector<std::vector<Eigen::Vector3d>>& rings) {
  PolygonTriangles result;
  result.status = PolygonStatus::degenerate;
  if (rings.empty()) return result;
  // Scale of the polygon, for tolerances.
  double extent = 0;
  for (const auto& ring : rings)
    for (const auto& p : ring) extent = std::max(extent, (p - rings[0][0]).cwiseAbs().maxCoeff());
  const double tolerance = 1e-9 * std::max(extent, 1e-300);
  std::vector<std::vector<std::uint32_t>> corners;
  std::uint32_t first = 0;
  for (const auto& ring : rings) {
    corners.push_back(distinct_corners(ring, first, tolerance));
    first += static_cast<std::uint32_t>(ring.size());
  }
  std::vector<Eigen::Vector3d> all;
  for (const auto& ring : rings) all.insert(all.end(), ring.begin(), ring.end());
  if (corners[0].size() < 3) return result;
  std::vector<Eigen::Vector3d> outer;
  for (auto k : corners[0]) outer.push_back(all[k]);
  const Eigen::Vector3d normal = newell_normal(outer);
  if (!(normal.norm() > 1e-12 * extent * extent)) return result;
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Vector3d origin = outer[0];
  const auto to_ring = [&](const std::vector<std::uint32_t>& ids) {
    Ring r;
    for (auto k : ids) r.push_back({k, Vec2((all[k] - origin).dot(u), (all[k] - origin).dot(v))});
    return r;
  };
  const double area_tolerance = 1e-12 * extent * extent;
  Ring outline = to_ring(corners[0]);  // counter-clockwise about n by construction of u, v
  drop_collinear(outline, area_tolerance);
  if (outline.size() < 3) return result;
  if (signed_area(outline) < 0) std::reverse(outline.begin(), outline.end());
  std::vector<Ring> holes;
  for (std::size_t h = 1; h < corners.size(); ++h) {
    Ring hole = to_ring(corners[h]);
    drop_collinear(hole, area_tolerance);
    if (hole.size() < 3 || std::abs(signed_area(hole)) <= area_tolerance) continue;  // a hole of no area
    if (signed_area(hole) > 0) std::reverse(hole.begin(), hole.end());
    holes.push_back(std::move(hole));
  }
  // Rightmost hole first, so that a bridge never has to pass a hole not yet joined.
  std::sort(holes.begin(), holes.end(), [](const Ring& a, const Ring& b) {
    const auto max_x = [](const Ring& r) {
      double x = -std::numeric_limits<double>::infinity();
      for (const Corner& c : r) x = std::max(x, c.p.x());
      return x;
    };
    return max_x(a) > max_x(b);
  });
  bool valid = true;
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const std::vector<Ring> rest(holes.begin() + static_cast<std::ptrdiff_t>(h) + 1, holes.end());
    valid = bridge(outline, holes[h], rest) && valid;
  }
  if (std::abs(signed_area(outline)) <= area_tolerance) return result;
  valid = clip_ears(std::move(outline), area_tolerance, result.triangles) && valid;
  result.status = valid ? PolygonStatus::ok : PolygonStatus::partial;
  if (result.triangles.empty()) result.status = valid ? PolygonStatus::degenerate : PolygonStatus::partial;
  return result;
}

}  // namespace attenuvis::visgraph
