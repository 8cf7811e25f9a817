// Plane geometry the ground and footprint code needs from CGAL: the Delaunay
// triangulation of scattered points and the simplicity test of a ring.
// Internal to the visgraph library.  CGAL's headers take a long time to
// compile, so everything that includes them lives in one translation unit
// (cgal/planar.cpp), built apart with CGAL's compile options
// (visgraph/CMakeLists.txt).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

// The Delaunay triangulation of `points` (CGAL's Delaunay_triangulation_2 on
// exact predicates): indices into `points`, each triangle counter-clockwise
// seen from +z.  Repeated points are used once (the first); fewer than three
// points, or all of them on one line, give no triangle.
std::vector<std::array<std::uint32_t, 3>> delaunay_triangles(const std::vector<Eigen::Vector2d>& points);

// True when the closed ring through `ring` (first vertex not repeated at the
// end, no two consecutive vertices equal) has no two edges that meet except
// consecutive edges at their shared vertex (CGAL::is_simple_2, exact
// predicates).  A ring that touches itself at a vertex is not simple.
bool ring_is_simple(const std::vector<Eigen::Vector2d>& ring);

}  // namespace attenuvis::visgraph::detail
