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

// A triangle mesh with a group (and optionally a class) per triangle, and the CRS
// of its coordinates.
struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // For each triangle, an index into `groups`: the OBJ group (or, where the
  // file has none, its material) the triangle came from.  Walkable surfaces
  // are selected by these names (e.g. "sidewalk", "crosswalk").
  std::vector<std::uint32_t> triangle_group;
  std::vector<std::string> groups;
  // Surface class of each triangle, an index into `classes`: for CityJSON its
  // semantic surface type (RoofSurface, GroundSurface, ...) or, without
  // semantics, its city object's type (TINRelief, Road, Building, ...).
  // Empty when the source has no classes (OBJ, glTF, generated scenes).
  std::vector<std::uint32_t> triangle_class;
  std::vector<std::string> classes;
  // Coordinate reference system as the file names it (CityJSON
  // metadata.referenceSystem, e.g. "urn:ogc:def:crs:EPSG::28992"); empty
  // when unknown.
  std::string crs;

  std::size_t add_group(const std::string& name);  // index of name, added if new
  std::size_t add_class(const std::string& name);  // likewise for classes
};

// Horizontal (xy-projected) area of the triangles in the named groups: the
// number of nodes a 1 m grid on those surfaces gives, to within edge effects.
double walkable_area(const Mesh& mesh, const std::vector<std::string>& groups);

// A horizontal rectangle at the lowest z of the mesh, covering its xy
// bounding box grown by `margin` metres: ground for a model that has none
// (buildings only).  Group kGroundPlaneGroup; class kGroundPlaneClass where
// the mesh has classes.  Facing up.
inline constexpr const char* kGroundPlaneGroup = "ground-plane";
inline constexpr const char* kGroundPlaneClass = "GroundPlane";
void add_ground_plane(Mesh& mesh, double margin = 1.0);
// The same rectangle at height z (ground.hpp chooses it for a given height).
void add_ground_plane_at(Mesh& mesh, double z, double margin = 1.0);

// For messages: the first `shown` names, comma-separated, then
// " ... and N more" and, if given, `more_hint` (e.g. "(`attenuvis scene info
// FILE --groups` lists them)"), so that a message stays one short line
// whatever the scene.
std::string preview_names(const std::vector<std::string>& names, std::size_t shown = 5,
                          const std::string& more_hint = "");

// Triangles and projected area per group and per class, largest first.
struct MeshStats {
  struct Group {
    std::string name;
    std::size_t triangles = 0;
    double projected_area = 0.0;  // m^2, as walkable_area
    std::vector<std::string> classes;  // groups only: the classes of its triangles, in mesh order
  };
  std::size_t vertices = 0, triangles = 0;
  Eigen::Vector3d lower, upper;   // bounding box of the vertices used by triangles
  std::vector<Group> groups;
  std::vector<Group> classes;     // empty when the mesh has no classes
};
// The statistics `scene info` prints.
MeshStats mesh_stats(const Mesh& mesh);

}  // namespace attenuvis::visgraph
