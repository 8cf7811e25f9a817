// A triangle mesh in world coordinates (metres), as read from OBJ or made by a
// scene generator.  Coordinates are kept in double: Embree works in float, so
// the scene recentres them before building its BVH (see scene.hpp).
#pragma once

#include <Eigen/Core>

#include <array>
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

// Reads an OBJ file; polygons are triangulated, groups and materials kept.
// Throws std::runtime_error naming the file (and line, where one is to blame)
// for an unreadable file, NaN/inf vertices, bad indices or an empty mesh.
Mesh load_obj(const std::string& path);

// Writes the mesh as OBJ, one `g` block per group, atomically (temporary
// file renamed into place).
void write_obj(const Mesh& mesh, const std::string& path);

}  // namespace attenuvis::visgraph
