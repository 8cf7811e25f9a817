// Ground under a model that has none: most cities publish their buildings
// without terrain, and eye points need something to stand on.
//
// Each building (a mesh group: a CityJSON city object, an OBJ group) says
// where the ground meets it: the vertices of its GroundSurface, or, without
// one, the lower ends of its vertical wall edges, or, without those, its
// lowest vertex.  These base points decide the ground:
//  - when every one lies within kFlatBaseTolerance of the model's lowest z, a
//    horizontal plane there is the ground (add_ground_plane, mesh.hpp): the
//    model is flat, and a plane covers it all;
//  - otherwise the ground is inferred: the Delaunay triangulation of the base
//    points (at their own heights) over their convex hull, a TIN that passes
//    through every building's base and interpolates linearly between them.
//    Outside the hull nothing is known, and nothing is invented.
// A plane under bases that stand higher than the eye above it would put eye
// points below those buildings (lines of sight then pass under them): asked
// for at the lowest z it is refused, asked for at a given z it is counted.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// The group and CityGML-like class of the inferred ground's triangles.
inline constexpr const char* kInferredGroundGroup = "inferred-ground";
inline constexpr const char* kInferredGroundClass = "InferredGround";
// Base points within this height of the lowest z (m) count as one flat
// ground: LoD2 models put the bases of a flat district on one height or
// within centimetres of it, well under an eye height.
inline constexpr double kFlatBaseTolerance = 0.5;

// The base points of a model's buildings, from which the ground is inferred.
struct BuildingBases {
  // One point per distinct footprint position (xy to 1 mm), at the lowest
  // base height any building gives there.
  std::vector<Eigen::Vector3d> points;
  // Per building that gave points: its lowest base height (m), and its group.
  std::vector<double> building_base;
  std::vector<std::uint32_t> building_group;
  // How the bases were found: buildings with a GroundSurface, with vertical
  // wall edges only, and with neither (their lowest vertex).
  std::size_t from_ground_surface = 0, from_walls = 0, from_lowest_vertex = 0;
  double lowest = 0, highest = 0;  // z range of the points (0, 0 when there are none)
};

// The base points of every group of the mesh (see above).
BuildingBases building_bases(const Mesh& mesh);

// Adds the Delaunay TIN of the base points (group kInferredGroundGroup; class
// kInferredGroundClass where the mesh has classes; facing up) and returns its
// triangle count.  Throws std::invalid_argument when the points do not span
// an area (fewer than three, or all on one line).
std::size_t add_inferred_ground(Mesh& mesh, const BuildingBases& bases);

// Where a buildings-only model's ground comes from.
enum class GroundRule {
  automatic,     // a plane at the lowest z when the bases are flat, else the inferred TIN
  lowest_plane,  // a plane at the lowest z; refused when bases stand above the eye
  plane_at,      // a plane at GroundRequest::plane_z, as asked
};

// The ground asked for: a rule and its parameters.
struct GroundRequest {
  GroundRule rule = GroundRule::automatic;
  double plane_z = 0;       // m, for plane_at
  double eye_height = 1.7;  // m: a base higher than this above a plane leaves eyes under it
};

// The ground that was made, in numbers, for the run's report.
struct GroundMade {
  bool inferred = false;       // a TIN; otherwise a plane at plane_z
  double plane_z = 0;
  std::size_t buildings = 0;   // buildings that gave base points
  std::size_t points = 0, triangles = 0;  // of the TIN
  double lowest = 0, highest = 0;         // base heights, m
  // Buildings whose base stands more than the eye height above the plane
  // (plane_at only: lowest_plane refuses them).
  std::size_t floating = 0;
  std::string description;  // where the ground came from, in words, for reports
};

// Gives a model without ground one, by the rule asked for (see above).
// Throws std::invalid_argument for lowest_plane when a building's base
// stands more than the eye height above the plane (naming the range of the
// bases and the alternatives), and for an automatic choice that needs a TIN
// the bases cannot make.
GroundMade add_ground(Mesh& mesh, const GroundRequest& request);

}  // namespace attenuvis::visgraph
