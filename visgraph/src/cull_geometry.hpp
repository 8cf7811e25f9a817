// The scene's triangles as the culling tests need them: exactly the float
// vertices Embree intersects (read back from its buffers, widened to
// double), a bounding-volume hierarchy queried by a convex shaft, and the
// planar convex occluders (a triangle, or two coplanar triangles sharing an
// edge that form a convex quad).  Internal to the visgraph library.
//
// Why a hierarchy of our own: Embree's queries are rays, spheres
// (rtcPointQuery) and collisions between user geometries (rtcCollide); the
// question "does any triangle meet this convex hull" is none of them.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

struct Box3 {
  double lo[3], hi[3];
};

// The sight lines of one packet: from `point` to partners (x[l], y[l],
// z[l]), l < n <= 16, their bounding box and the squared length of the
// longest (its root is taken only by the quads that need it).
// The partners are copied into 16 aligned lanes, the idle ones repeating
// partner 0, so that every lane test loads whole vectors and needs no
// bounds (each test masks the idle lanes out of its answer).
struct PacketLines {
  const double* point = nullptr;
  alignas(64) double x[16], y[16], z[16];
  int n = 0;
  Box3 box;
  double longest_squared = 0;
};
// The lines from `point` to partners (x[l], y[l], z[l]), l < n, 1 <= n <= 16.
void set_lines(PacketLines& lines, const double* point, const double* x, const double* y, const double* z, int n);

class CullGeometry {
 public:
  CullGeometry(RTCScene scene, std::size_t triangle_count);

  double max_abs_coordinate() const { return max_abs_; }
  // True when no triangle meets the convex hull of boxes a and b grown by
  // `margin` (conservative: false whenever the proof fails).
  bool hull_is_empty(const Box3& a, const Box3& b, double margin) const;
  // True when the occluder of `triangle` separates a from b with `margin`
  // (pair_culling.hpp).
  bool occluder_blocks(std::uint32_t triangle, const Box3& a, const Box3& b, double margin) const;
  // True when the closed convex solid `triangle` belongs to (if any) blocks
  // every segment from a to b: both boxes outside it by `margin`, and the
  // crossings of the 64 corner-to-corner segments with the plane through the
  // solid's centre normal to the centre-to-centre direction inside it by
  // `margin` (every segment then passes through its interior, so enters it
  // through its watertight surface).
  bool solid_blocks(std::uint32_t triangle, const Box3& a, const Box3& b, double margin) const;
  // The same two tests (planar occluder, convex solid) for each sight line
  // of a packet, from its point to each partner: the case of boxes that are
  // points, without their setup.  The bit mask of the lanes whose segment
  // the occluder or the solid of `triangle` blocks with `margin` (the
  // partners' box gives a quick answer when the occluder's plane does not
  // pass between the point and any of them).
  // With with_solid false, the planar occluder alone (the caller has tried
  // the triangle's solid on these lanes already).
  std::uint32_t lanes_blocked(std::uint32_t triangle, const PacketLines& lines, double margin,
                              bool with_solid = true) const;
  // The solid of a triangle, or -1: callers skip a solid already tried.
  std::int32_t solid_of(std::uint32_t triangle) const { return solid_of_[triangle]; }

  // A planar occluder: a triangle, or a convex quad of two (see
  // build_occluders).  A sight line is blocked by it when both ends lie at
  // least margin + depth from its plane, on either side, and it crosses
  // the plane at least `inside` within every edge (lanes_blocked).
  struct Occluder {
    double n[3], c;           // plane n.x = c, |n| = 1
    int edges = 0;            // 3 or 4; 0: degenerate, blocks nothing
    double u[4][3], o[4];     // inward in-plane edge normals: u.x - o >= 0 inside
    double depth = 0;         // a quad's second triangle: largest distance from the plane
    // A face of a closed convex solid: the sign of n.x - c inside the
    // solid (+1 or -1); 0 for any other occluder.
    int inside_sign = 0;
  };
  const std::vector<Occluder>& occluders() const { return occluders_; }

 private:
  struct Triangle {
    double v[3][3];
  };
  struct BvhNode {
    double lo[3], hi[3];
    std::uint32_t first = 0, count = 0;  // leaf: triangles order_[first, first + count)
    std::int32_t left = -1, right = -1;
  };
  struct Solid {
    std::vector<std::array<double, 4>> faces;  // outward unit normal n and c: inside n.x - c <= 0
    double centre[3];
    double slack = 0;  // largest distance of a vertex beyond a face plane (non-planar quads)
  };
  static std::uint32_t occluder_lanes(const Occluder& o, double sa, double side, double inside,
                                      const PacketLines& lines);
  // The lanes whose segment `solid` blocks (lanes_blocked's solid test).
  static std::uint32_t solid_lanes(const Solid& solid, double margin, const PacketLines& lines);
  std::uint32_t build(std::uint32_t first, std::uint32_t count, std::vector<double>& centroid);
  void build_occluders(const unsigned* index);
  void pair_quad_triangles(const unsigned* index, std::vector<std::uint32_t>& partner,
                           std::vector<std::uint8_t>& shared_edge) const;
  Occluder occluder(std::size_t t, std::uint32_t u, const std::vector<std::uint8_t>& shared_edge) const;
  void build_solids(const unsigned* index);
  bool convex_solid(const std::vector<std::uint32_t>& tris, Solid& solid) const;
  void merge_coplanar_faces(const std::vector<std::uint32_t>& tris, double size, Solid& solid) const;

  std::vector<Triangle> tris_;
  std::vector<std::uint32_t> order_;
  std::vector<BvhNode> bvh_;
  std::vector<Occluder> occluders_;
  std::vector<std::uint32_t> occluder_of_;
  std::vector<Solid> solids_;
  std::vector<std::int32_t> solid_of_;
  double max_abs_ = 0;
};

}  // namespace attenuvis::visgraph::detail
