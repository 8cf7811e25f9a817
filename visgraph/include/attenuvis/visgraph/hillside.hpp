// A synthetic hillside town published as buildings only, as most cities
// publish theirs: no terrain, each building's GroundSurface on the (known)
// ground.  The test of the inferred ground (ground.hpp) and its benchmark:
// the ground is a 20 % slope along x with a ridge along it,
//
//     z(x, y) = slope x - ridge_curvature (y - size / 2)^2,
//
// so that every second directional derivative is bounded by
// M = 2 ridge_curvature, and linear interpolation over a triangle whose
// smallest enclosing circle has radius R is within M R^2 / 2 of it (Waldron,
// "The error in linear interpolation at the vertices of a simplex", SIAM J.
// Numer. Anal. 35(3), 1998, Theorem 3.1).  The ridge is also convex enough
// to hide eyes from one another over it (a chord of d metres clears the
// ground's mid-point by at most M d^2 / 8: 4 m over 200 m).
//
// Determinism as the synthetic city (city.hpp): raw mt19937_64 output,
// polynomial geometry.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <cstdint>

namespace attenuvis::visgraph {

// The generated hillside town: its slope, size, blocks and buildings.
struct HillsideOptions {
  std::uint64_t seed = 20;          // the slope in per cent
  double size = 200.0;              // m, the town's side along x and y
  double slope = 0.2;               // rise per metre along x
  double ridge_curvature = 4e-4;    // 1/m: 4 m of ridge over +-100 m
  double block = 40.0;              // m, pitch of the square blocks
  double street = 10.0;             // m, between blocks
  double height_min = 6.0, height_max = 20.0;  // m, above each building's lowest corner
};

// The true ground under the town.
double hillside_ground(const HillsideOptions& options, double x, double y);
// M: the largest second directional derivative of hillside_ground.
double hillside_curvature_bound(const HillsideOptions& options);

// Four buildings per block, each a flat-roofed prism on a rectangle of
// 7 to 11 m turned by up to 15 degrees within its quarter of the block; its
// floor (GroundSurface) and its walls' feet on the ground at each corner, its
// roof `height` above the lowest corner (footprints.hpp).  One group per
// building ("building-N"), classes GroundSurface, WallSurface, RoofSurface;
// no terrain.
Mesh hillside_town(const HillsideOptions& options = {});

}  // namespace attenuvis::visgraph
