// The five classic 50x50 m visibility test layouts attenuvis ships as code
// (the seed paper's test scenes).  Coordinates are metres, z up.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <vector>

namespace attenuvis::visgraph {

// Classic layouts: a 50x50 m floor [0,50]^2 at z=0 (group scene_group::floor) and
// obstacles 10 m tall as closed boxes (group scene_group::obstacle).
constexpr int kClassicLayoutCount = 5;
constexpr double kClassicLayoutSize = 50.0;
constexpr double kClassicObstacleHeight = 10.0;

// Axis-aligned footprint [x0,x1] x [y0,y1] of one obstacle box.
struct Footprint {
  double x0, x1, y0, y1;
};

// index 0..4: "four-L-walls", "T-block", "single-block", "plus-block", "two-walls".
// Throws std::invalid_argument for any other index.
const char* classic_layout_name(int index);
std::vector<Footprint> classic_layout_obstacles(int index);
Mesh classic_layout(int index);

}  // namespace attenuvis::visgraph
