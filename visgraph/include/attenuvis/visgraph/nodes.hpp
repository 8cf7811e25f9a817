// Observer nodes: eye positions whose lines of sight form the graph.
//
// Generated nodes follow the seed paper (and DHART's graph generator): a
// square grid of cell centres over the scene's footprint; a ray cast straight
// down from above the scene finds the first surface under each cell centre;
// if that surface is walkable the node is the hit point raised by the eye
// height.  A cell whose first hit is not walkable (a roof, an obstacle top)
// is covered and dropped, as is one whose surface is too steep or whose eye
// would be inside geometry (no headroom between surface and eye).
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

struct NodeGridOptions {
  double spacing = 1.0;     // m, grid pitch (cell centres at min + (i + 1/2) spacing)
  double eye_height = 1.7;  // m above the walkable surface
  // Names of walkable groups; empty = every surface is walkable.
  std::vector<std::string> walkable;
  double max_slope_deg = 90.0;  // surfaces steeper than this are not walkable
};

struct NodeSet {
  std::vector<Eigen::Vector3d> eyes;  // world frame
  std::size_t cells = 0;              // grid cells examined
  std::size_t no_surface = 0;         // ray down hit nothing
  std::size_t covered = 0;            // first surface hit not walkable
  std::size_t too_steep = 0;
  std::size_t no_headroom = 0;        // geometry between surface and eye
};

// Throws std::invalid_argument for a non-positive/non-finite spacing or eye
// height, or a walkable group name that the scene does not contain.
NodeSet generate_nodes(const Scene& scene, const NodeGridOptions& options);

// Reads eye positions from a CSV file: one `x,y,z` per line (world frame,
// metres), optional header line, '#' comments.  Throws naming file and line
// for malformed or non-finite values, or a file with no nodes.
std::vector<Eigen::Vector3d> read_nodes_csv(const std::string& path);

// Parses "x,y,z" (e.g. a --target-point argument).
Eigen::Vector3d parse_point(const std::string& text);

}  // namespace attenuvis::visgraph
