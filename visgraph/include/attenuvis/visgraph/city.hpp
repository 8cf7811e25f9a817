// A seedable synthetic city attenuvis ships as code, in the spirit of the
// seed paper's CityEngine scene (Schwartz, Vinnikov, Federici, SimAUD 2021).
// Coordinates are metres, z up.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph {

// Synthetic city.  Street centre lines form a hexagonal tiling (pointy-top
// hexagons of side `hex_size`, `rings` rings around a central one); each hex
// cell is a block surrounded by a `road_width` street.  Inside the block's
// edge runs a `sidewalk_width` sidewalk; at both ends of every street between
// two blocks a crosswalk `crosswalk_width` long spans the road from sidewalk
// to sidewalk.  The rest of the block is a lot ("ground") with buildings of
// random height along its sides (or an open park).  Everything sits on a
// smooth random height field of `relief` metres peak to trough.
//
// OBJ groups (names in scene_spec.hpp, scene_group): sidewalk, crosswalk,
// road, ground (lots and parks), building, terrain (natural ground under and around the city, lying
// `subgrade` metres below the paved surfaces so that a ray cast down on the
// city hits the pavement first, never a coincident terrain triangle).
//
// Walkable surfaces (sidewalk, crosswalk, road, ground) are triangulated finely
// enough to follow the terrain: every vertex has z = terrain(x, y) exactly.
// Buildings are closed prisms whose base lies `foundation` metres below the
// lowest terrain point of their footprint.
//
// Determinism: the only random source is std::mt19937_64 seeded with `seed`,
// whose output sequence the C++ standard fixes; uniform numbers are made from
// its raw 64-bit output (top 53 bits) rather than std::uniform_*_distribution,
// whose output is implementation-defined.  The height field is a polynomial
// (no exp/sin) and the geometry uses only + - * / and sqrt, so coordinates are
// bit-identical across platforms given IEEE double arithmetic without fused
// multiply-add contraction: true of baseline x86-64 builds; a build for an
// FMA-capable -march may differ in the last bits (GCC contracts by default
// in C++), which the fingerprint test in tests/visgraph/test_generators.cpp
// would report.
struct CityOptions {
  std::uint64_t seed = 2021;       // the seed paper's year: the documented default
  int rings = 4;                   // 1 + 3 rings (rings + 1) blocks: 61 by default
  double hex_size = 62.5;          // m, side (= circumradius) of the street-centre-line hexagon
  double road_width = 10.0;        // m, curb to curb
  double sidewalk_width = 2.0;     // m
  double crosswalk_width = 3.0;    // m, measured along the street
  double relief = 6.0;             // m, terrain peak to trough over the city's bounding box
  double margin = 40.0;            // m of terrain beyond the outermost streets
  double building_height_min = 6.0;
  double building_height_max = 45.0;
  double park_fraction = 0.1;      // probability that a block is an open park
  double paved_max_edge = 4.0;     // m, largest triangle edge on sidewalks and roads
  double ground_max_edge = 8.0;    // m, on lots and parks
  double terrain_spacing = 10.0;   // m, grid of the natural terrain
  double subgrade = 0.2;           // m, natural terrain below the paved surfaces
  double foundation = 0.5;         // m, building base below its lowest terrain point
};

// Smooth random terrain: z = offset + tilt . (x, y) + sum_k a_k (1 - r_k^2/s_k^2)^3
// (bumps of compact support, C^2), scaled so that its range over the city's
// bounding box (sampled on a 10 m grid) is `relief` with minimum 0.
struct HeightField {
  struct Bump {
    double x, y, radius, amplitude;
  };
  std::vector<Bump> bumps;
  double tilt_x = 0.0, tilt_y = 0.0, scale = 1.0, offset = 0.0;
  double operator()(double x, double y) const;
};

// One hexagonal block of the synthetic city: its sidewalk ring and its lot.
struct CityBlock {
  Eigen::Vector2d centre;
  double outer_apothem;       // m, block edge (outer edge of the sidewalk), centre to side
  double lot_apothem;         // m, inner edge of the sidewalk
  bool park;                  // no buildings
};

// A street-centre-line junction: degree 3 inside the city, 2 on its rim.
struct CityIntersection {
  Eigen::Vector3d position;   // on the terrain
  int degree;
};

// A crossing of a street between two blocks' sidewalks.
struct CityCrosswalk {
  Eigen::Vector3d centre;     // on the terrain, middle of the crossing
  Eigen::Vector2d across;     // unit, from one sidewalk to the other
  double length;              // m across the road (= road_width)
  double width;               // m along the street (= crosswalk_width)
  std::array<int, 2> blocks;  // the two blocks it connects
  int intersection;           // index of the junction it is next to
};

// The corner of a block's sidewalk, at the middle of the sidewalk's width,
// on the bisector of the block corner: where a pedestrian waits to cross.
struct CitySidewalkCorner {
  Eigen::Vector3d position;   // on the terrain
  Eigen::Vector2d outward;    // unit, from the block centre towards the junction
  int block;
  int intersection;           // index of the junction the corner faces
};

// A box building on a block's lot, set into the terrain.
struct CityBuilding {
  std::array<Eigen::Vector2d, 4> footprint;  // convex, counter-clockwise
  double base_z, top_z;
  int block;
};

// The synthetic city: its mesh and the parts it was built from.
struct City {
  Mesh mesh;
  HeightField terrain;
  std::vector<CityBlock> blocks;
  std::vector<CityIntersection> intersections;
  std::vector<CityCrosswalk> crosswalks;
  std::vector<CitySidewalkCorner> sidewalk_corners;
  std::vector<CityBuilding> buildings;
};

// Throws std::invalid_argument for options that make no city (negative
// widths, a road so wide the blocks vanish, ...).
City make_city(const CityOptions& options);
Mesh synthetic_city(const CityOptions& options);  // make_city(options).mesh

// The same as make_city's walkable geometry would give, in closed form:
// blocks * 2 sqrt(3) w (2 a - w) + interior streets * 2 * road_width * crosswalk_width,
// a = block outer apothem, w = sidewalk width.  For sizing the city.
double city_walkable_area_estimate(const CityOptions& options);

}  // namespace attenuvis::visgraph
