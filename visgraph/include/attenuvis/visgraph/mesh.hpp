// A triangle mesh in world coordinates (metres), as read from a file or made
// by a scene generator, and the small measures reports and tests use.
// Coordinates are kept in double: Embree works in float, so the scene
// recentres them before building its BVH (see scene.hpp).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // For each triangle, an index into `groups`: the OBJ group (or, where the
  // file has none, its material) the triangle came from.  Walkable surfaces
  // are selected by these names (e.g. "sidewalk", "crosswalk").
  std::vector<std::uint32_t> triangle_group;
  std::vector<std::string> groups;

  std::size_t add_group(const std::string& name);  // index of name, added if new
};

// Horizontal (xy-projected) area of the triangles in the named groups: the
// number of nodes a 1 m grid on those surfaces gives, to within edge effects.
double walkable_area(const Mesh& mesh, const std::vector<std::string>& groups);

struct MeshStats {
  struct Group {
    std::string name;
    std::size_t triangles = 0;
    double projected_area = 0.0;  // m^2, as walkable_area
  };
  std::size_t vertices = 0, triangles = 0;
  Eigen::Vector3d lower, upper;   // bounding box of the vertices used by triangles
  std::vector<Group> groups;
};
MeshStats mesh_stats(const Mesh& mesh);

}  // namespace attenuvis::visgraph
