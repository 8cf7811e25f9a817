// Observer nodes: eye positions whose lines of sight form the graph.
//
// Generated nodes follow the seed paper (and DHART's graph generator): a
// square grid of cell centres over the scene's footprint; a ray cast straight
// down from above the scene meets the surfaces under each cell centre, and
// the node is the standing surface's point raised by the eye height.  Which
// surface people stand on:
//  - named walkable groups or classes (NodeGridOptions::walkable; "*" = every
//    surface): the FIRST surface under the cell, if it is walkable; a cell
//    whose first surface is not (a roof, an obstacle top) is covered;
//  - nothing named, scene with classes (CityJSON): the same rule with
//    default_walkable_classes(): terrain, roads, squares, land use, ground
//    surfaces, the ground plane; never a roof;
//  - nothing named, scene without classes (OBJ, glTF): the LOWEST surface
//    under the cell (a pavement lying up to 0.5 m over a terrain counts as
//    the same ground: the top one is taken), provided the eye above it is
//    outside every closed solid, i.e. an even number of surfaces lies above
//    the eye; otherwise the cell is covered (inside or under a building).
// Cells are also dropped where the surface is too steep or the eye would be
// inside geometry (no headroom between surface and eye).  Each node's
// surface is compared with the lowest surface under its cell: a node
// standing more than `elevated_height` above it is counted as elevated (a
// roof, a bridge deck), for a warning.
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// The most grid cells a node grid may have without --allow-large.
constexpr double kDefaultMaxGridCells = 1e7;

// Where node_grid() places eye points.
struct NodeGridOptions {
  double spacing = 1.0;     // m, grid pitch (cell centres at min + (i + 1/2) spacing)
  double eye_height = 1.7;  // m above the walkable surface
  // Names of walkable groups or classes; "*" = every surface; empty = the
  // scene's data decide (see above).
  std::vector<std::string> walkable;
  double max_slope_deg = 90.0;  // surfaces steeper than this are not walkable
  double elevated_height = 2.0; // m above the lowest surface under the cell
  // Refuse grids of more cells than this (0 = no limit): each cell costs
  // ~100 bytes and a few rays, so 1e7 cells are ~1 GB and a minute.
  double max_cells = kDefaultMaxGridCells;
};

// Cells of the grid generate_nodes would examine (a double: a 1 mm grid over
// a country overflows any integer), and the bytes they take while placed.
struct GridEstimate {
  double nx = 0, ny = 0, cells = 0;
  double bytes = 0;
};
GridEstimate estimate_grid(const Scene& scene, double spacing);

// Classes people walk on by default (CityJSON city-object types and semantic
// surfaces, including CityJSON 2.0 names): TINRelief, Road, TransportSquare,
// Square, LandUse, TrafficArea, AuxiliaryTrafficArea, GroundSurface, and the
// grounds attenuvis adds: GroundPlane (add_ground_plane), InferredGround
// (ground.hpp) and DEMTerrain (terrain.hpp).  Never RoofSurface.
std::vector<std::string> default_walkable_classes();

// How many nodes stand on one class (or group, in a scene without classes).
struct SurfaceCount {
  std::string name;
  std::size_t nodes = 0;
};

// The eye points of a grid, and where they stand.
struct NodeSet {
  std::vector<Eigen::Vector3d> eyes;  // world frame
  double spacing = 0;                 // m, the grid's spacing
  std::string spacing_rule;           // how the spacing was chosen, in words (set by the caller; "" = as given)
  std::size_t cells = 0;              // grid cells examined
  std::size_t no_surface = 0;         // ray down hit nothing
  std::size_t covered = 0;            // first surface hit not walkable
  std::size_t too_steep = 0;
  std::size_t no_headroom = 0;        // geometry between surface and eye
  std::string rule;                   // the placement rule used, in words
  std::vector<SurfaceCount> by_surface;  // most nodes first
  std::size_t elevated = 0;           // nodes more than elevated_height above the lowest surface
  double max_elevation = 0;           // m, largest such height among all nodes
  std::vector<Eigen::Vector2d> covered_cells;  // world xy of covered cell centres (building footprints)
};

// Throws std::invalid_argument for a spacing, eye height or slope outside
// the ranges of limits.hpp, a grid of more than max_cells cells or of more
// memory than the machine has, or a walkable name that is neither a group
// nor a class of the scene.
NodeSet generate_nodes(const Scene& scene, const NodeGridOptions& options);

// True when the grid stood on the scene's own ground.  In a scene with classes:
// some triangle has a walkable class other than GroundSurface (a building's
// floor lies under its roof: no ground to stand on).  Otherwise: more cells
// got a node than found no surface at all.  False for a model of buildings
// without terrain: add_ground (ground.hpp) gives it one.
bool found_ground(const Scene& scene, const NodeSet& grid);

// Reads eye positions from a CSV file: one `x,y,z` per line (world frame,
// metres), optional header line, '#' comments.  Throws naming file and line
// for malformed or non-finite values, or a file with no nodes.
std::vector<Eigen::Vector3d> read_nodes_csv(const std::string& path);

// Reads eye positions from a node file, GeoJSON points (geojson.hpp: the
// text starts with '{') or CSV (read_nodes_csv).  `crs`, if given, receives
// the GeoJSON file's crs name (empty for CSV or none).
std::vector<Eigen::Vector3d> read_nodes(const std::string& path, std::string* crs = nullptr);

// Parses "x,y,z" (e.g. a --target-point argument).
Eigen::Vector3d parse_point(const std::string& text);

}  // namespace attenuvis::visgraph
