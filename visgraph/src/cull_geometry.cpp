// Shaft queries and planar occluders over Embree's own triangles
// (cull_geometry.hpp; the proofs behind the tests are in pair_culling.hpp).
#include "cull_geometry.hpp"
#include "cull_math.hpp"
#include "lane_isa.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

namespace attenuvis::visgraph::detail {

namespace {
using namespace cull_math;

// Convex hull of two grown boxes, as the separating-axis tests see it.
struct Shaft {
  double centre[2][3], half[2][3];  // the two grown boxes
  double lo[3], hi[3];
  double dir[3];
  bool has_dir = false;
  double axis[3][3], amin[3], amax[3];
  int axes = 0;

  // The hull projects onto the hull of the boxes' projections, and a box
  // onto its centre's projection +- sum |n_c| half_c: two dot products
  // instead of sixteen corners' (the same interval in exact arithmetic;
  // either rounding is a few ulps of the coordinates, far inside the
  // margin the boxes are grown by).
  void project(const double* n, double& lo_out, double& hi_out) const {
    const double abs_n[3] = {std::abs(n[0]), std::abs(n[1]), std::abs(n[2])};
    const double p0 = dot(n, centre[0]), r0 = dot(abs_n, half[0]);
    const double p1 = dot(n, centre[1]), r1 = dot(abs_n, half[1]);
    lo_out = std::min(p0 - r0, p1 - r1);
    hi_out = std::max(p0 + r0, p1 + r1);
  }
  // True when axis n separates the hull from points p[0..count).
  bool separates(const double* n, const double (*p)[3], int count) const {
    if (dot(n, n) < 1e-24) return false;
    double hl, hh;
    project(n, hl, hh);
    double pl = dot(n, p[0]), ph = pl;
    for (int k = 1; k < count; ++k) {
      const double v = dot(n, p[k]);
      pl = std::min(pl, v);
      ph = std::max(ph, v);
    }
    return ph < hl || pl > hh;
  }
};

Shaft make_shaft(const Box3& a, const Box3& b, double g) {
  Shaft s;
  for (int c = 0; c < 3; ++c) {
    s.centre[0][c] = 0.5 * (a.lo[c] + a.hi[c]), s.half[0][c] = 0.5 * (a.hi[c] - a.lo[c]) + g;
    s.centre[1][c] = 0.5 * (b.lo[c] + b.hi[c]), s.half[1][c] = 0.5 * (b.hi[c] - b.lo[c]) + g;
    s.lo[c] = std::min(a.lo[c], b.lo[c]) - g;
    s.hi[c] = std::max(a.hi[c], b.hi[c]) + g;
    s.dir[c] = s.centre[1][c] - s.centre[0][c];
  }
  s.has_dir = dot(s.dir, s.dir) > 0;
  if (s.has_dir)
    for (int c = 0; c < 3; ++c) {
      double e[3] = {0, 0, 0};
      e[c] = 1;
      const V3 n = cross(s.dir, e);
      if (dot(n.data(), n.data()) < 1e-24 * dot(s.dir, s.dir)) continue;
      std::copy(n.begin(), n.end(), s.axis[s.axes]);
      s.project(s.axis[s.axes], s.amin[s.axes], s.amax[s.axes]);
      ++s.axes;
    }
  return s;
}

bool boxes_overlap(const double* alo, const double* ahi, const double* blo, const double* bhi) {
  for (int c = 0; c < 3; ++c)
    if (ahi[c] < blo[c] || alo[c] > bhi[c]) return false;
  return true;
}

// No quad partner (build_occluders), or no occluder yet.
constexpr std::uint32_t kNone = 0xFFFFFFFFu;

}  // namespace

CullGeometry::CullGeometry(RTCScene scene, std::size_t triangle_count) {
  RTCGeometry geometry = rtcGetGeometry(scene, 0);
  const auto* vertex = static_cast<const float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
  const auto* index = static_cast<const unsigned*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_INDEX, 0));
  if (!vertex || !index) throw std::runtime_error("visibility: the scene's triangles are not readable for culling");
  tris_.resize(triangle_count);
  std::vector<double> centroid(3 * triangle_count);
  for (std::size_t t = 0; t < triangle_count; ++t)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        const double v = vertex[3 * index[3 * t + k] + c];
        tris_[t].v[k][c] = v;
        centroid[3 * t + c] += v / 3;
        max_abs_ = std::max(max_abs_, std::abs(v));
      }
  order_.resize(triangle_count);
  std::iota(order_.begin(), order_.end(), 0u);
  bvh_.reserve(2 * triangle_count / 2 + 1);
  build(0, static_cast<std::uint32_t>(triangle_count), centroid);
  build_occluders(index);
  build_solids(index);
}

// Median split on the longest side of the centroids' box; leaves of <= 4.
std::uint32_t CullGeometry::build(std::uint32_t first, std::uint32_t count, std::vector<double>& centroid) {
  const auto id = static_cast<std::uint32_t>(bvh_.size());
  bvh_.emplace_back();
  BvhNode node;
  double clo[3], chi[3];
  for (int c = 0; c < 3; ++c) node.lo[c] = clo[c] = INFINITY, node.hi[c] = chi[c] = -INFINITY;
  for (std::uint32_t k = first; k < first + count; ++k) {
    const Triangle& t = tris_[order_[k]];
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) node.lo[c] = std::min(node.lo[c], t.v[v][c]), node.hi[c] = std::max(node.hi[c], t.v[v][c]);
    for (int c = 0; c < 3; ++c)
      clo[c] = std::min(clo[c], centroid[3 * order_[k] + c]), chi[c] = std::max(chi[c], centroid[3 * order_[k] + c]);
  }
  if (count <= 4) {
    node.first = first;
    node.count = count;
    bvh_[id] = node;
    return id;
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (chi[c] - clo[c] > chi[axis] - clo[axis]) axis = c;
  const std::uint32_t half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::uint32_t a, std::uint32_t b) { return centroid[3 * a + axis] < centroid[3 * b + axis]; });
  node.left = static_cast<std::int32_t>(build(first, half, centroid));
  node.right = static_cast<std::int32_t>(build(first + half, count - half, centroid));
  bvh_[id] = node;
  return id;
}

// One occluder per triangle, or per pair of triangles that share an edge
// (same vertex indices, so Embree's watertight test leaves no crack between
// them), lie in one plane to within 1e-6 of their size and form a convex
// quad.  `depth` holds the second triangle's distance from the first one's
// plane (used as an extra margin).
void CullGeometry::build_occluders(const unsigned* index) {
  const std::size_t T = tris_.size();
  occluder_of_.assign(T, kNone);
  std::vector<std::uint32_t> partner(T, kNone);
  std::vector<std::uint8_t> shared_edge(T, 0);  // edge k = (v_k, v_k+1) shared with the partner
  pair_quad_triangles(index, partner, shared_edge);
  for (std::size_t t = 0; t < T; ++t) {
    if (occluder_of_[t] != kNone) continue;
    occluder_of_[t] = static_cast<std::uint32_t>(occluders_.size());
    if (partner[t] != kNone) occluder_of_[partner[t]] = occluder_of_[t];
    occluders_.push_back(occluder(t, partner[t], shared_edge));
  }
}

// Pairs each triangle with at most one neighbour across a shared edge that
// lies in its plane and makes a convex quad with it: partner[t] (or
// kNone) and shared_edge[t], the index k of t's edge (v_k, v_k+1)
// they share.
void CullGeometry::pair_quad_triangles(const unsigned* index, std::vector<std::uint32_t>& partner,
                                       std::vector<std::uint8_t>& shared_edge) const {
  std::unordered_map<std::uint64_t, std::uint32_t> first_on_edge;
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t e = edge_key(index[3 * t + k], index[3 * t + (k + 1) % 3]);
      const auto [it, fresh] = first_on_edge.emplace(e, static_cast<std::uint32_t>(t));
      if (fresh) continue;
      const std::uint32_t u = it->second;
      if (partner[t] != kNone || partner[u] != kNone || u == t) continue;
      // Coplanar and convex?
      const auto [nt, at] = unit_normal(tris_[t].v);
      const auto [nu, au] = unit_normal(tris_[u].v);
      if (at == 0 || au == 0 || std::abs(dot(nt.data(), nu.data())) < 1 - 1e-12) continue;
      int apex_u = 0;
      for (int j = 0; j < 3; ++j)
        if (index[3 * u + j] != index[3 * t + k] && index[3 * u + j] != index[3 * t + (k + 1) % 3]) apex_u = j;
      const double* a = tris_[t].v[k];
      const double* c = tris_[t].v[(k + 1) % 3];
      const double* b = tris_[t].v[(k + 2) % 3];
      const double* d = tris_[u].v[apex_u];
      const V3 ac = sub(c, a), ab = sub(b, a), ad = sub(d, a), bd = sub(d, b), ba = sub(a, b), bc = sub(c, b);
      const double side_b = dot(cross(ac.data(), ab.data()).data(), nt.data());
      const double side_d = dot(cross(ac.data(), ad.data()).data(), nt.data());
      const double side_a = dot(cross(bd.data(), ba.data()).data(), nt.data());
      const double side_c = dot(cross(bd.data(), bc.data()).data(), nt.data());
      if (!(side_b * side_d < 0 && side_a * side_c < 0)) continue;
      const double size = std::sqrt(std::max(at, au));
      if (std::abs(dot(nt.data(), ad.data())) > 1e-6 * size) continue;
      partner[t] = u;
      partner[u] = static_cast<std::uint32_t>(t);
      shared_edge[t] = static_cast<std::uint8_t>(k);
      for (int j = 0; j < 3; ++j)
        if (j != apex_u && (j + 1) % 3 != apex_u) shared_edge[u] = static_cast<std::uint8_t>(j);
    }
  }
}

// The occluder of triangle t and its quad partner u (kNone: none):
// the polygon in t's plane, with u's apex projected onto it, and its
// inward edge normals.  A degenerate triangle or edge gives an occluder of
// no edges, which blocks nothing.
CullGeometry::Occluder CullGeometry::occluder(std::size_t t, std::uint32_t u,
                                              const std::vector<std::uint8_t>& shared_edge) const {
  Occluder o;
  const auto [n, area] = unit_normal(tris_[t].v);
  if (area == 0) return o;  // degenerate: never an occluder
  std::copy(n.begin(), n.end(), o.n);
  o.c = dot(o.n, tris_[t].v[0]);
  std::vector<V3> poly = {V3{tris_[t].v[0][0], tris_[t].v[0][1], tris_[t].v[0][2]},
                          V3{tris_[t].v[1][0], tris_[t].v[1][1], tris_[t].v[1][2]},
                          V3{tris_[t].v[2][0], tris_[t].v[2][1], tris_[t].v[2][2]}};
  double depth = 0;
  if (u != kNone) {
    // The quad in order: u's apex (opposite its shared edge) between the
    // shared edge's ends (k, k + 1) of t: v_k, apex, v_k+1, v_k+2.
    const double* p = tris_[u].v[(shared_edge[u] + 2) % 3];
    const double s = dot(o.n, p) - o.c;
    depth = std::abs(s);
    const V3 projected = {p[0] - s * o.n[0], p[1] - s * o.n[1], p[2] - s * o.n[2]};
    poly.insert(poly.begin() + static_cast<std::ptrdiff_t>(shared_edge[t] + 1), projected);
  }
  o.edges = static_cast<int>(poly.size());
  V3 centre = {0, 0, 0};
  for (const V3& p : poly)
    for (int c = 0; c < 3; ++c) centre[c] += p[c] / static_cast<double>(poly.size());
  for (int k = 0; k < o.edges; ++k) {
    const V3& p0 = poly[static_cast<std::size_t>(k)];
    const V3& p1 = poly[static_cast<std::size_t>((k + 1) % o.edges)];
    const V3 e = sub(p1.data(), p0.data());
    V3 w = cross(o.n, e.data());
    const double l = norm(w);
    if (l == 0) {
      o.edges = 0;  // degenerate edge
      break;
    }
    w = {w[0] / l, w[1] / l, w[2] / l};
    if (dot(w.data(), sub(centre.data(), p0.data()).data()) < 0) w = {-w[0], -w[1], -w[2]};
    std::copy(w.begin(), w.end(), o.u[k]);
    o.o[k] = dot(w.data(), p0.data());
  }
  o.depth = depth;
  // A triangle's unused fourth edge passes every test (lanes_blocked runs
  // four edges for all occluders).
  for (int k = o.edges; k < 4; ++k) {
    o.u[k][0] = o.u[k][1] = o.u[k][2] = 0;
    o.o[k] = -INFINITY;
  }
  return o;
}

bool CullGeometry::hull_is_empty(const Box3& a, const Box3& b, double margin) const {
  const Shaft s = make_shaft(a, b, margin);
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  // A hull among many triangles that are near it but not in it is costly to
  // prove empty and rarely is: give up (undecided, the conservative answer)
  // after a fixed amount of work, so a test never costs more than a few
  // packets of rays.
  int budget = 512;
  while (top > 0) {
    if (--budget < 0) return false;
    const BvhNode& node = bvh_[stack[--top]];
    if (!boxes_overlap(node.lo, node.hi, s.lo, s.hi)) continue;
    bool outside = false;
    for (int k = 0; k < s.axes && !outside; ++k) {
      const double* n = s.axis[k];
      double centre = 0, radius = 0;
      for (int c = 0; c < 3; ++c) {
        centre += n[c] * 0.5 * (node.lo[c] + node.hi[c]);
        radius += std::abs(n[c]) * 0.5 * (node.hi[c] - node.lo[c]);
      }
      outside = centre + radius < s.amin[k] || centre - radius > s.amax[k];
    }
    if (outside) continue;
    if (node.left >= 0) {
      if (top + 2 > 128) return false;  // deeper than any tree built here; give up (conservative)
      stack[top++] = static_cast<std::uint32_t>(node.left);
      stack[top++] = static_cast<std::uint32_t>(node.right);
      continue;
    }
    for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
      const Triangle& t = tris_[order_[k]];
      double tlo[3], thi[3];
      for (int c = 0; c < 3; ++c) {
        tlo[c] = std::min({t.v[0][c], t.v[1][c], t.v[2][c]});
        thi[c] = std::max({t.v[0][c], t.v[1][c], t.v[2][c]});
      }
      if (!boxes_overlap(tlo, thi, s.lo, s.hi)) continue;
      budget -= 8;
      bool separated = false;
      for (int q = 0; q < s.axes && !separated; ++q) separated = s.separates(s.axis[q], t.v, 3);
      const V3 e[3] = {sub(t.v[1], t.v[0]), sub(t.v[2], t.v[1]), sub(t.v[0], t.v[2])};
      if (!separated) separated = s.separates(cross(e[0].data(), e[1].data()).data(), t.v, 3);
      for (int q = 0; q < 3 && !separated && s.has_dir; ++q)
        separated = s.separates(cross(e[q].data(), s.dir).data(), t.v, 3);
      for (int q = 0; q < 3 && !separated; ++q)
        for (int c = 0; c < 3 && !separated; ++c) {
          double axis[3] = {0, 0, 0};
          axis[c] = 1;
          separated = s.separates(cross(e[q].data(), axis).data(), t.v, 3);
        }
      if (!separated) return false;
    }
  }
  return true;
}

bool CullGeometry::occluder_blocks(std::uint32_t triangle, const Box3& a, const Box3& b, double margin) const {
  const Occluder& o = occluders_[occluder_of_[triangle]];
  if (o.edges == 0) return false;
  double ca[8][3], cb[8][3], sa[8], sb[8];
  const int na = distinct_corners(a, ca), nb = distinct_corners(b, cb);
  double a_lo = INFINITY, a_hi = -INFINITY, b_lo = INFINITY, b_hi = -INFINITY;
  for (int k = 0; k < na; ++k) {
    sa[k] = dot(o.n, ca[k]) - o.c;
    a_lo = std::min(a_lo, sa[k]), a_hi = std::max(a_hi, sa[k]);
  }
  for (int k = 0; k < nb; ++k) {
    sb[k] = dot(o.n, cb[k]) - o.c;
    b_lo = std::min(b_lo, sb[k]), b_hi = std::max(b_hi, sb[k]);
  }
  // A quad's second triangle may stand off the plane by `depth`: both boxes
  // must clear it, and a sight line meeting the plane at angle theta crosses
  // that triangle up to depth / sin(theta) from where it crosses the plane,
  // sin(theta) >= (nearest |s| in A + nearest |s| in B) / longest corner pair.
  const double side = margin + o.depth;
  const bool a_below = a_hi <= -side && b_lo >= side;
  const bool a_above = a_lo >= side && b_hi <= -side;
  if (!a_below && !a_above) return false;
  double inside = margin;
  if (o.depth > 0) {
    const double s_min = std::min(std::abs(a_lo), std::abs(a_hi)) + std::min(std::abs(b_lo), std::abs(b_hi));
    double longest = 0;
    for (int c = 0; c < 3; ++c) {
      const double span = std::max(a.hi[c], b.hi[c]) - std::min(a.lo[c], b.lo[c]);
      longest += span * span;
    }
    inside += o.depth + o.depth * std::sqrt(longest) / s_min;
  }
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j) {
      const double t = sa[i] / (sa[i] - sb[j]);
      double p[3];
      for (int c = 0; c < 3; ++c) p[c] = ca[i][c] + t * (cb[j][c] - ca[i][c]);
      for (int k = 0; k < o.edges; ++k)
        if (dot(o.u[k], p) - o.o[k] < inside) return false;
    }
  return true;
}

// The lanes of lanes_blocked that a planar occluder blocks, given the row's
// signed distance sa from its plane (|sa| >= side) and the margin inside
// its edges: a branch-free loop over the lanes (a triangle's unused fourth
// edge always passes), vectorised per instruction set.
//
// Without a division.  The crossing of the line from a to q with the plane
// is p = a + t (q - a), t = s_a / D, D = s_a - s_b.  A lane that passes the
// side test has s_b beyond the plane on the far side, so D has the sign of
// s_a and |D| = |s_a| + sign s_b >= |s_a| + side > 0; each edge test
// u.p - o >= inside, multiplied by |D|, reads
//     (u.a - o - inside) |D| + |s_a| (u.q - u.a) >= 0.
// The same comparison in exact arithmetic; the rounding of either form is a
// few ulps of the coordinates, far inside the margin.  The unused fourth
// edge (u = 0, o = -inf) gives +inf: it passes.
namespace {
// What the lane loop needs of the occluder and the row.
struct LaneTest {
  const double* n;
  double c;
  const double (*u)[3];
  double ua[4], rest[4];  // u.a and u.a - o - inside per edge
  double sign, abs_sa, side;
};

// The lane loop in portable code, one clone per instruction set below
// AVX-512 (which takes occluder_lane_bits_avx512).
#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target_clones("avx2", "default")))
#endif
std::uint32_t occluder_lane_bits(const LaneTest& t, const PacketLines& lines) {
  int ok[16];
  for (int l = 0; l < 16; ++l) {
    const double qx = lines.x[l], qy = lines.y[l], qz = lines.z[l];
    const double sb = t.n[0] * qx + t.n[1] * qy + t.n[2] * qz - t.c;
    const double abs_d = t.abs_sa + t.sign * sb;
    bool pass = t.sign * sb >= t.side;
    for (int k = 0; k < 4; ++k)
      pass &= t.rest[k] * abs_d + t.abs_sa * (t.u[k][0] * qx + t.u[k][1] * qy + t.u[k][2] * qz - t.ua[k]) >= 0;
    ok[l] = pass ? 1 : 0;
  }
  std::uint32_t blocked = 0;
  for (int l = 0; l < 16; ++l) blocked |= static_cast<std::uint32_t>(ok[l]) << l;
  return blocked;
}

#ifdef ATTENUVIS_X86_DISPATCH
// The same loop on AVX-512 with its comparisons kept in mask registers:
// GCC turns the portable loop's sixteen flags into a bit mask with shifts
// and a tree of ORs, a quarter of the loop's time.
__attribute__((target("avx512f"))) std::uint32_t occluder_lane_bits_avx512(const LaneTest& t,
                                                                          const PacketLines& lines) {
  const __m512d n0 = _mm512_set1_pd(t.n[0]), n1 = _mm512_set1_pd(t.n[1]), n2 = _mm512_set1_pd(t.n[2]);
  const __m512d c = _mm512_set1_pd(t.c), sign = _mm512_set1_pd(t.sign), abs_sa = _mm512_set1_pd(t.abs_sa);
  const __m512d side = _mm512_set1_pd(t.side), zero = _mm512_setzero_pd();
  std::uint32_t blocked = 0;
  for (int h = 0; h < 2; ++h) {
    const __m512d qx = _mm512_load_pd(lines.x + 8 * h), qy = _mm512_load_pd(lines.y + 8 * h);
    const __m512d qz = _mm512_load_pd(lines.z + 8 * h);
    const __m512d sb = _mm512_sub_pd(_mm512_fmadd_pd(n2, qz, _mm512_fmadd_pd(n1, qy, _mm512_mul_pd(n0, qx))), c);
    const __m512d signed_sb = _mm512_mul_pd(sign, sb);
    const __m512d abs_d = _mm512_add_pd(abs_sa, signed_sb);
    __mmask8 pass = _mm512_cmp_pd_mask(signed_sb, side, _CMP_GE_OQ);
    for (int k = 0; k < 4; ++k) {
      const __m512d uq = _mm512_fmadd_pd(_mm512_set1_pd(t.u[k][2]), qz,
                                         _mm512_fmadd_pd(_mm512_set1_pd(t.u[k][1]), qy,
                                                         _mm512_mul_pd(_mm512_set1_pd(t.u[k][0]), qx)));
      const __m512d e = _mm512_fmadd_pd(_mm512_set1_pd(t.rest[k]), abs_d,
                                        _mm512_mul_pd(abs_sa, _mm512_sub_pd(uq, _mm512_set1_pd(t.ua[k]))));
      pass = _mm512_mask_cmp_pd_mask(pass, e, zero, _CMP_GE_OQ);
    }
    blocked |= static_cast<std::uint32_t>(pass) << (8 * h);
  }
  return blocked;
}
#endif

using LaneBits = std::uint32_t (*)(const LaneTest&, const PacketLines&);
LaneBits pick_lane_bits() {
#ifdef ATTENUVIS_X86_DISPATCH
  if (pick_isa() == Isa::avx512) return occluder_lane_bits_avx512;
#endif
  return occluder_lane_bits;
}
}  // namespace

std::uint32_t CullGeometry::occluder_lanes(const Occluder& o, double sa, double side, double inside,
                                           const PacketLines& lines) {
  static const LaneBits lane_bits = pick_lane_bits();
  LaneTest t;
  t.n = o.n, t.c = o.c, t.u = o.u;
  t.sign = sa < 0 ? 1.0 : -1.0;  // the partner must be beyond +side (row below) or -side (row above)
  t.abs_sa = std::abs(sa);
  t.side = side;
  const double* a = lines.point;
  for (int k = 0; k < 4; ++k) {
    t.ua[k] = o.u[k][0] * a[0] + o.u[k][1] * a[1] + o.u[k][2] * a[2];
    t.rest[k] = t.ua[k] - o.o[k] - inside;
  }
  return lane_bits(t, lines) & ((1u << lines.n) - 1u);
}

namespace {
// One step of set_lines' fold: lanes [0, W) take the min / max with lanes
// [W, 2W).  A constant width, so that each step is straight vector code.
template <int W>
inline void fold_lanes(double (&lo)[3][8], double (&hi)[3][8], double (&longest)[8]) {
  for (int l = 0; l < W; ++l) {
    for (int c = 0; c < 3; ++c) {
      lo[c][l] = std::min(lo[c][l], lo[c][l + W]);
      hi[c][l] = std::max(hi[c][l], hi[c][l + W]);
    }
    longest[l] = std::max(longest[l], longest[l + W]);
  }
}
}  // namespace

// Branch-free over the 16 lanes (the idle ones repeat partner 0, which
// changes neither the box nor the longest line), vectorised per instruction
// set like the lane tests.  GCC does not vectorise a floating-point min or
// max reduction (it would reorder NaN and signed-zero cases), so the lanes
// are folded elementwise, 16 into 8, then 8 into 4, 2 and 1: each step is a
// vector operation, where one running minimum over 16 lanes was a chain of
// 16 dependent scalar instructions.  Min, max and the squared lengths are
// exact in any order, so the box and the longest line are the same values.
ATTENUVIS_CULL_CLONES
void set_lines(PacketLines& lines, const double* point, const double* x, const double* y, const double* z, int n) {
  lines.point = point;
  lines.n = n;
  if (n == 16) {
    // Element loops, not std::copy: GCC turns the copies into three calls
    // of memmove.
    for (int l = 0; l < 16; ++l) lines.x[l] = x[l], lines.y[l] = y[l], lines.z[l] = z[l];
  } else {
    for (int l = 0; l < 16; ++l) {
      const int j = l < n ? l : 0;
      lines.x[l] = x[j], lines.y[l] = y[j], lines.z[l] = z[j];
    }
  }
  const double px = point[0], py = point[1], pz = point[2];
  alignas(64) double lo[3][8], hi[3][8], longest[8];
  for (int l = 0; l < 8; ++l) {
    const double* q[3] = {lines.x, lines.y, lines.z};
    for (int c = 0; c < 3; ++c) {
      lo[c][l] = std::min(q[c][l], q[c][l + 8]);
      hi[c][l] = std::max(q[c][l], q[c][l + 8]);
    }
    const double dx0 = lines.x[l] - px, dy0 = lines.y[l] - py, dz0 = lines.z[l] - pz;
    const double dx1 = lines.x[l + 8] - px, dy1 = lines.y[l + 8] - py, dz1 = lines.z[l + 8] - pz;
    longest[l] = std::max(dx0 * dx0 + dy0 * dy0 + dz0 * dz0, dx1 * dx1 + dy1 * dy1 + dz1 * dz1);
  }
  fold_lanes<4>(lo, hi, longest);
  fold_lanes<2>(lo, hi, longest);
  fold_lanes<1>(lo, hi, longest);
  for (int c = 0; c < 3; ++c) lines.box.lo[c] = lo[c][0], lines.box.hi[c] = hi[c][0];
  lines.longest_squared = longest[0];
}

std::uint32_t CullGeometry::lanes_blocked(std::uint32_t triangle, const PacketLines& lines, double margin,
                                          bool with_solid) const {
  // The planar occluder for all lanes at once, branch-free (a triangle's
  // unused fourth edge never fails).  A quad's depth
  // term uses a bound for all lanes: |q - point| <= the longest line,
  // |s_a| + |s_b| >= |s_a| + side: a larger margin, never a smaller one.
  const double* point = lines.point;
  const int n = lines.n;
  std::uint32_t blocked = 0;
  const Occluder& o = occluders_[occluder_of_[triangle]];
  const double sa = dot(o.n, point) - o.c;
  const double side = margin + o.depth;
  // Some of the partners' box beyond the plane on the far side, by `side`.
  double far_side = sa < 0 ? -o.c : o.c;
  for (int c = 0; c < 3; ++c) {
    const double mid = 0.5 * (lines.box.lo[c] + lines.box.hi[c]), half = 0.5 * (lines.box.hi[c] - lines.box.lo[c]);
    far_side += (sa < 0 ? o.n[c] : -o.n[c]) * mid + std::abs(o.n[c]) * half;
  }
  if (o.edges > 0 && std::abs(sa) >= side && far_side >= side) {
    const double inside =
        margin + (o.depth > 0 ? o.depth + o.depth * std::sqrt(lines.longest_squared) / (std::abs(sa) + side) : 0.0);
    blocked = occluder_lanes(o, sa, side, inside, lines);
  }
  const std::uint32_t all = (1u << n) - 1u;
  if (blocked == all || !with_solid || solid_of_[triangle] < 0) return blocked;
  return blocked | solid_lanes(solids_[static_cast<std::size_t>(solid_of_[triangle])], margin, lines);
}

}  // namespace attenuvis::visgraph::detail
