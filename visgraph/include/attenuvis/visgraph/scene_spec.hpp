// Scenes named on the command line ("layout:N", "city", "city:SEED"): the
// one place that knows their group names and which of them people walk on.
#pragma once

#include <attenuvis/visgraph/city.hpp>
#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/mesh.hpp>

#include <string>
#include <vector>

namespace attenuvis::visgraph {

// Group names of the shipped scenes (the OBJ `g` names `scene --out` writes).
namespace scene_group {
// Classic layouts.
inline constexpr const char* floor = "floor";
inline constexpr const char* obstacle = "obstacle";
// Synthetic city.
inline constexpr const char* sidewalk = "sidewalk";
inline constexpr const char* crosswalk = "crosswalk";
inline constexpr const char* road = "road";
inline constexpr const char* ground = "ground";  // lots and parks
inline constexpr const char* building = "building";
inline constexpr const char* terrain = "terrain";
}  // namespace scene_group

// Where pedestrians stand in the shipped scenes: the floor of a classic
// layout; the sidewalks and crosswalks of the city (the seed paper's choice).
std::vector<std::string> classic_layout_walkable_groups();
std::vector<std::string> city_walkable_groups();

// "layout:N" (N = 0..4) or "city" or "city:SEED"; anything else throws
// std::invalid_argument.  `city` options other than the seed come from `base`.
bool is_scene_spec(const std::string& text);
Mesh scene_from_spec(const std::string& spec, const CityOptions& base = {});

// The walkable groups of a scene spec (as above); empty for anything that is
// not a scene spec (a file: its own data decide, see nodes.hpp).
std::vector<std::string> default_walkable_groups(const std::string& scene);

}  // namespace attenuvis::visgraph
