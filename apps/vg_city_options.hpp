// The options of `attenuvis vg` that take city models from what cities
// publish and give results back to a GIS: a DEM to stand on (--terrain),
// footprints extruded by a height field (--height-field, --levels-field,
// --storey-height, --strict), the ground under buildings-only models
// (--ground-plane) and the GeoPackage output (--gpkg).  They are turned into
// the library's typed values here (visgraph/gis/city.hpp, ground.hpp).
#pragma once

#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/gis/city.hpp>

#include <CLI/CLI.hpp>

#include <string>

namespace attenuvis::cli {

struct CityArguments {
  std::string terrain;
  std::string height_field, levels_field;
  double storey_height = 3.0;
  bool strict = false;
  std::string gpkg;
  std::string ground_plane = "auto";  // auto | yes | no | Z
  bool allow_large = false;           // lifts the terrain's cell limit (vg's --allow-large)
};

// Adds --terrain, --height-field, --levels-field, --storey-height, --strict,
// --gpkg and --ground-plane to `vg`.
void add_city_options(CLI::App* vg, CityArguments& a);

// True when the options ask for a DEM or footprints (which need a scene file).
bool wants_city_input(const CityArguments& a);

// What --ground-plane asks for: nothing (no), a ground only where the model
// has none (auto), or a plane now (yes: the lowest z; Z: that height).
struct GroundPlaneChoice {
  bool automatic = false, now = false;
  visgraph::GroundRequest request;
};
// Throws std::invalid_argument for anything but auto, yes, no or a height in metres.
GroundPlaneChoice ground_plane_choice(const CityArguments& a, double eye_height);

// Gives the mesh the ground asked for (visgraph::add_ground); a refusal
// says which options give another ground.
visgraph::GroundMade make_ground(visgraph::Mesh& mesh, const visgraph::GroundRequest& request);

// The library's options for reading the scene file; `nodes_given`: the eyes
// come from --nodes (the DEM is then checked under each of them).
visgraph::gis::CityOptions city_options(const CityArguments& a, const visgraph::SceneFileOptions& file,
                                        bool nodes_given);

}  // namespace attenuvis::cli
