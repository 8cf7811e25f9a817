// The closed convex solids of the culling geometry: connected sets of
// triangles that bound a convex volume, and the test that one blocks every
// segment between two boxes (cull_geometry.hpp; the proof is in
// pair_culling.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cull_geometry.hpp"
#include "cull_math.hpp"

namespace attenuvis::visgraph::detail {

namespace {
using namespace cull_math;

// The sets of triangles connected through shared vertex indices (union-find
// over the vertex indices), keyed by a root vertex.
std::unordered_map<unsigned, std::vector<std::uint32_t>> connected_triangles(const unsigned* index, std::size_t T) {
  unsigned max_vertex = 0;
  for (std::size_t k = 0; k < 3 * T; ++k) max_vertex = std::max(max_vertex, index[k]);
  std::vector<unsigned> parent(static_cast<std::size_t>(max_vertex) + 1);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](unsigned v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::size_t t = 0; t < T; ++t) {
    const unsigned a = find(index[3 * t]), b = find(index[3 * t + 1]), c = find(index[3 * t + 2]);
    parent[b] = a;
    parent[find(c)] = a;
  }
  std::unordered_map<unsigned, std::vector<std::uint32_t>> sets;
  for (std::size_t t = 0; t < T; ++t) sets[find(index[3 * t])].push_back(static_cast<std::uint32_t>(t));
  return sets;
}

// True when every edge of the triangles belongs to exactly two of them.
bool is_closed(const std::vector<std::uint32_t>& tris, const unsigned* index) {
  std::unordered_map<std::uint64_t, int> edge_uses;
  for (std::uint32_t t : tris)
    for (int k = 0; k < 3; ++k) ++edge_uses[edge_key(index[3 * t + k], index[3 * t + (k + 1) % 3])];
  bool closed = true;
  for (const auto& [edge, uses] : edge_uses) closed &= uses == 2;
  return closed;
}
}  // namespace

// Closed convex solids: connected sets of at most kMaxSolidTriangles
// triangles (through shared vertex indices) in which every edge belongs to
// exactly two triangles and every vertex lies behind every face plane (to
// within 1e-6 of the solid's size; the excess is kept as slack).  Buildings
// and obstacles made as closed boxes are such solids.
void CullGeometry::build_solids(const unsigned* index) {
  constexpr std::size_t kMaxSolidTriangles = 64;
  solid_of_.assign(tris_.size(), -1);
  std::unordered_map<unsigned, std::vector<std::uint32_t>> sets = connected_triangles(index, tris_.size());
  for (auto& [root, tris] : sets) {
    (void)root;
    if (tris.size() < 4 || tris.size() > kMaxSolidTriangles || !is_closed(tris, index)) continue;
    Solid solid;
    if (!convex_solid(tris, solid)) continue;
    const auto id = static_cast<std::int32_t>(solids_.size());
    for (std::uint32_t t : tris) {
      solid_of_[t] = id;
      Occluder& o = occluders_[occluder_of_[t]];
      if (o.edges) o.inside_sign = dot(o.n, solid.centre) - o.c < 0 ? -1 : 1;
    }
    solids_.push_back(std::move(solid));
  }
}

// The face planes of a closed set of triangles, outward, if every vertex
// lies behind every one of them (to within 1e-6 of the set's size, the
// excess kept as slack) and the centre strictly inside: a convex solid.
bool CullGeometry::convex_solid(const std::vector<std::uint32_t>& tris, Solid& solid) const {
  double centre[3] = {0, 0, 0}, size = 0;
  for (std::uint32_t t : tris)
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) centre[c] += tris_[t].v[v][c] / (3.0 * static_cast<double>(tris.size()));
  for (std::uint32_t t : tris)
    for (int v = 0; v < 3; ++v) size = std::max(size, norm(sub(tris_[t].v[v], centre)));
  bool convex = size > 0;
  for (std::uint32_t t : tris) {
    auto [n, l] = unit_normal(tris_[t].v);
    if (l == 0) continue;  // a degenerate triangle bounds nothing
    double c = dot(n.data(), tris_[t].v[0]);
    if (dot(n.data(), centre) - c > 0) n = {-n[0], -n[1], -n[2]}, c = -c;
    if (!(dot(n.data(), centre) - c < -1e-6 * size)) convex = false;  // centre on a face: flat, not a solid
    for (std::uint32_t u : tris)
      for (int v = 0; v < 3; ++v) {
        const double beyond = dot(n.data(), tris_[u].v[v]) - c;
        if (beyond > 1e-6 * size) convex = false;
        solid.slack = std::max(solid.slack, beyond);
      }
    solid.faces.push_back({n[0], n[1], n[2], c});
  }
  if (!convex) return false;
  merge_coplanar_faces(tris, size, solid);
  std::copy(centre, centre + 3, solid.centre);
  return true;
}

// The two triangles of a quad face give (nearly) one plane: keep one.  A
// plane dropped this way lies within `deviation` of the kept one at every
// vertex, which the slack covers.
void CullGeometry::merge_coplanar_faces(const std::vector<std::uint32_t>& tris, double size, Solid& solid) const {
  std::vector<std::array<double, 4>> kept;
  for (const auto& f : solid.faces) {
    bool duplicate = false;
    for (const auto& k : kept) {
      if (f[0] * k[0] + f[1] * k[1] + f[2] * k[2] < 1 - 1e-9) continue;
      double deviation = 0;
      for (std::uint32_t u : tris)
        for (int v = 0; v < 3; ++v) {
          const double* p = tris_[u].v[v];
          deviation = std::max(deviation, std::abs((f[0] * p[0] + f[1] * p[1] + f[2] * p[2] - f[3]) -
                                                   (k[0] * p[0] + k[1] * p[1] + k[2] * p[2] - k[3])));
        }
      if (deviation > 1e-6 * size) continue;
      solid.slack = std::max(solid.slack, deviation);
      duplicate = true;
      break;
    }
    if (!duplicate) kept.push_back(f);
  }
  solid.faces = std::move(kept);
}

bool CullGeometry::solid_blocks(std::uint32_t triangle, const Box3& a, const Box3& b, double margin) const {
  if (solid_of_[triangle] < 0) return false;
  const Solid& solid = solids_[static_cast<std::size_t>(solid_of_[triangle])];
  const double m = margin + solid.slack;
  double ca[8][3], cb[8][3];
  const int na = distinct_corners(a, ca), nb = distinct_corners(b, cb);
  // Both boxes outside the solid: beyond one face plane each.
  const auto outside = [&](const double (*corner)[3], int count) {
    for (const auto& f : solid.faces) {
      bool all = true;
      for (int k = 0; k < count && all; ++k)
        all = f[0] * corner[k][0] + f[1] * corner[k][1] + f[2] * corner[k][2] - f[3] >= m;
      if (all) return true;
    }
    return false;
  };
  if (!outside(ca, na) || !outside(cb, nb)) return false;
  double n[3];
  for (int c = 0; c < 3; ++c) n[c] = 0.5 * (b.lo[c] + b.hi[c]) - 0.5 * (a.lo[c] + a.hi[c]);
  const double length = std::sqrt(dot(n, n));
  if (!(length > 0)) return false;
  for (double& v : n) v /= length;
  const double c0 = dot(n, solid.centre);
  double sa[8], sb[8];
  for (int k = 0; k < na; ++k)
    if ((sa[k] = dot(n, ca[k]) - c0) > -m) return false;
  for (int k = 0; k < nb; ++k)
    if ((sb[k] = dot(n, cb[k]) - c0) < m) return false;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j) {
      const double t = sa[i] / (sa[i] - sb[j]);
      double p[3];
      for (int c = 0; c < 3; ++c) p[c] = ca[i][c] + t * (cb[j][c] - ca[i][c]);
      for (const auto& f : solid.faces)
        if (f[0] * p[0] + f[1] * p[1] + f[2] * p[2] - f[3] > -m) return false;
    }
  return true;
}

// lanes_blocked's solid test on the 16 lanes at once: the row outside
// (one face plane with the row at least m beyond it), each partner outside,
// and the crossing of the segment with the plane through the centre normal
// to it inside every face by m.  Branch-free over the lanes, faces
// outermost, so that each clone vectorises the lane loops.
//
// Without a square root or a division (GCC keeps std::sqrt scalar, and the
// divisions were most of the test's time).  With r = q - a, rr = |r|^2 and
// s = r.(centre - a), the signed distances of a and q from that plane are
// -s / |r| and (rr - s) / |r|, and the crossing is p = a + (s / rr) r.  So
//     s_a <= -m   reads  s >= 0 and s^2 >= m^2 rr,
//     s_b >= m    reads  rr - s >= 0 and (rr - s)^2 >= m^2 rr,
//     f.p - f_3 <= -m  reads  (f.a - f_3 + m) rr + s (f.r) <= 0,
// each the test it replaces multiplied by a positive factor (the same
// comparison in exact arithmetic; either rounding is a few ulps, far inside
// the margin).  A partner on the row (rr = 0) is never blocked.
ATTENUVIS_CULL_CLONES
std::uint32_t CullGeometry::solid_lanes(const Solid& solid, double margin, const PacketLines& lines) {
  const double m = margin + solid.slack;
  const double* a = lines.point;
  bool a_outside = false;
  for (const auto& f : solid.faces) a_outside |= f[0] * a[0] + f[1] * a[1] + f[2] * a[2] - f[3] >= m;
  if (!a_outside) return 0;
  const int n = lines.n;
  const double *qx = lines.x, *qy = lines.y, *qz = lines.z;
  const double cx = solid.centre[0] - a[0], cy = solid.centre[1] - a[1], cz = solid.centre[2] - a[2];
  const double m2 = m * m;
  alignas(64) double rx[16], ry[16], rz[16], rr[16], s[16];
  int ok[16];
  for (int l = 0; l < 16; ++l) {
    rx[l] = qx[l] - a[0], ry[l] = qy[l] - a[1], rz[l] = qz[l] - a[2];
    rr[l] = rx[l] * rx[l] + ry[l] * ry[l] + rz[l] * rz[l];
    s[l] = rx[l] * cx + ry[l] * cy + rz[l] * cz;
    const double beyond = rr[l] - s[l];
    ok[l] = ((rr[l] > 0) & (s[l] >= 0) & (s[l] * s[l] >= m2 * rr[l]) & (beyond >= 0) &
             (beyond * beyond >= m2 * rr[l]) & (l < n))
                ? 1
                : 0;
  }
  int b_outside[16] = {};
  for (const auto& f : solid.faces) {
    const double fa = f[0] * a[0] + f[1] * a[1] + f[2] * a[2] - f[3] + m;
    for (int l = 0; l < 16; ++l) {
      const double fr = f[0] * rx[l] + f[1] * ry[l] + f[2] * rz[l];
      b_outside[l] |= (f[0] * qx[l] + f[1] * qy[l] + f[2] * qz[l] - f[3] >= m) ? 1 : 0;
      ok[l] &= (fa * rr[l] + s[l] * fr <= 0) ? 1 : 0;
    }
  }
  std::uint32_t blocked = 0;
  for (int l = 0; l < 16; ++l) blocked |= static_cast<std::uint32_t>(ok[l] & b_outside[l]) << l;
  return blocked;
}

}  // namespace attenuvis::visgraph::detail
