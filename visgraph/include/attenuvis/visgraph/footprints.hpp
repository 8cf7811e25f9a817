// Buildings from footprints: a polygon (with holes, or several for a
// multipolygon) and a height, as national building registers, OpenStreetMap
// extracts and GIS layers publish them, extruded to prisms.  The GIS edge
// (visgraph/gis, GDAL) reads the layer into these typed values.
//
// Each footprint becomes a flat-roofed prism: a floor (GroundSurface), walls
// (WallSurface, one quad per ring edge, facing out) and a roof (RoofSurface)
// `height` metres above the lowest ground under the footprint, as
// OpenStreetMap's height is measured ("from the lowest point of ground
// contact").  Where it stands:
//  - on a terrain grid: the floor at the lowest terrain height under its
//    vertices (the uphill side of a house on a slope is buried in the hill);
//  - on its vertices' own z, when the layer has z (2.5-D footprints): the
//    floor through them, the roof `height` above the lowest;
//  - otherwise on a horizontal plane at plane_z.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/terrain.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace attenuvis::visgraph {

// One polygon of a footprint: its outline and holes.
struct FootprintPolygon {
  // rings[0] the outline, rings[1..] holes; each ring open (its first vertex
  // not repeated at the end) or closed, either orientation.
  std::vector<std::vector<Eigen::Vector3d>> rings;
};

// A building as a footprint (one or more polygons) and a height.
struct BuildingFootprint {
  std::string id;  // the feature's id, for messages and as the prism's group
  std::vector<FootprintPolygon> polygons;
  double height = 0;  // m, > 0
};

// What the extruded prisms stand on.
struct FootprintGround {
  const HeightGrid* terrain = nullptr;  // stand on it (takes precedence)
  bool vertex_z = false;                // stand on the vertices' own z
  double plane_z = 0;                   // otherwise: stand on this plane, m
};

// The prisms, one group per footprint (its id) with classes GroundSurface,
// WallSurface and RoofSurface.  Throws std::invalid_argument naming `source`
// and the footprint's id for a ring with fewer than three distinct vertices,
// a ring that intersects itself, a polygon that cannot be triangulated (a
// hole outside its outline), a coordinate outside the range of limits.hpp,
// a ring of more than kMaxPolygonVertices vertices, a height that is not a
// positive finite number or that the base rises by more than across the
// footprint, or a footprint with no terrain height under any vertex.
Mesh extrude_footprints(const std::vector<BuildingFootprint>& footprints, const FootprintGround& ground,
                        const std::string& source);

}  // namespace attenuvis::visgraph
