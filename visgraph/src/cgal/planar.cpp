// planar.hpp on CGAL: the only translation unit that includes CGAL (its
// headers are slow to compile, and its -frounding-math stays here).
#include "../planar.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <utility>

namespace attenuvis::visgraph::detail {

namespace {
// Exact predicates (orientation, in-circle) on double coordinates: the
// triangulation is a true Delaunay triangulation of the given points, whatever
// their rounding; nothing here constructs new points.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
}  // namespace

std::vector<std::array<std::uint32_t, 3>> delaunay_triangles(const std::vector<Eigen::Vector2d>& points) {
  std::vector<std::pair<Kernel::Point_2, std::uint32_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()), static_cast<std::uint32_t>(i));
  // The range constructor sorts the points along a Hilbert curve before
  // inserting them: O(n log n) in practice.
  const Delaunay triangulation(input.begin(), input.end());
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(triangulation.number_of_faces());
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end(); ++face)
    triangles.push_back({face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()});
  return triangles;  // CGAL's faces are counter-clockwise
}

bool ring_is_simple(const std::vector<Eigen::Vector2d>& ring) {
  std::vector<Kernel::Point_2> points;
  points.reserve(ring.size());
  for (const Eigen::Vector2d& p : ring) points.emplace_back(p.x(), p.y());
  return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

}  // namespace attenuvis::visgraph::detail
