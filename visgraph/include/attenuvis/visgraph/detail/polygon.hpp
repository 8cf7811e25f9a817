// Triangulation of one planar polygon with holes, as city models store their
// faces (CityJSON surfaces, glTF/OBJ n-gons): concave outlines, collinear and
// repeated vertices, holes.  Degenerate input is reported, never fatal.
// Not part of the public interface: the CityJSON reader's, here for its
// tests.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph {

enum class PolygonStatus {
  ok,            // triangulated
  degenerate,    // zero area (fewer than 3 distinct corners, or all collinear): no triangles
  partial,       // self-intersecting or otherwise invalid: the triangles found so far
};

struct PolygonTriangles {
  // Indices into the concatenation of the rings (outer ring first, then each
  // hole, in the order given).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  PolygonStatus status = PolygonStatus::ok;
};

// rings[0] is the outer boundary, rings[1..] holes; a ring may repeat its first
// vertex at the end.  The polygon is projected on the plane of its Newell
// normal and ear-clipped (holes joined to the outline by bridges); repeated
// consecutive vertices are dropped and collinear corners clipped without
// making zero-area triangles.  Triangles keep the outer ring's orientation.
PolygonTriangles triangulate_polygon(const std::vector<std::vector<Eigen::Vector3d>>& rings);

}  // namespace attenuvis::visgraph
