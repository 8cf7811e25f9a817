// `vg`'s city-model options (vg_city_options.hpp).
#include "vg_city_options.hpp"

#include <attenuvis/io/number_text.hpp>
#include <attenuvis/visgraph/limits.hpp>

#include <stdexcept>

namespace attenuvis::cli {

namespace vg = attenuvis::visgraph;

void add_city_options(CLI::App* cmd, CityArguments& a) {
  cmd->add_option("--ground-plane", a.ground_plane,
                  "auto | yes | no | Z: the ground of a model without one (auto: a plane at its lowest z when the "
                  "building bases agree within 0.5 m, else the ground inferred from the bases; yes: the plane, "
                  "refused when bases stand above the eye; Z: a plane at height Z m)")
      ->capture_default_str();
  cmd->add_option("--terrain", a.terrain,
                  "DEM to stand on (GeoTIFF or any raster GDAL reads, in the model's CRS, covering it; cells "
                  "without data only under buildings)");
  cmd->add_option("--height-field", a.height_field,
                  "the scene is a layer of footprints (GeoPackage, Shapefile, GeoJSON, ...): extrude each polygon "
                  "by this field (m)");
  cmd->add_option("--levels-field", a.levels_field,
                  "footprints: storeys, where the height field has no value (e.g. building:levels)");
  cmd->add_option("--storey-height", a.storey_height, "footprints: metres per storey for --levels-field")
      ->capture_default_str();
  cmd->add_flag("--strict", a.strict, "footprints: a feature without a usable height is an error (default: skipped, counted)");
  cmd->add_option("--gpkg", a.gpkg, "GeoPackage point layer of the nodes, every score a field, in the scene's CRS");
}

bool wants_city_input(const CityArguments& a) {
  return !a.terrain.empty() || !a.height_field.empty() || !a.levels_field.empty();
}

GroundPlaneChoice ground_plane_choice(const CityArguments& a, double eye_height) {
  GroundPlaneChoice choice;
  choice.request.eye_height = eye_height;
  if (a.ground_plane == "auto") {
    choice.automatic = true;
    choice.request.rule = vg::GroundRule::automatic;
  } else if (a.ground_plane == "yes") {
    choice.now = true;
    choice.request.rule = vg::GroundRule::lowest_plane;
  } else if (a.ground_plane != "no") {
    double z = 0;
    try {
      z = io::parse_double(a.ground_plane, "--ground-plane");
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("--ground-plane: expected auto, yes, no or a height in metres, got '" +
                                  a.ground_plane + "'");
    }
    vg::check_coordinate(z, "--ground-plane");
    choice.now = true;
    choice.request.rule = vg::GroundRule::plane_at;
    choice.request.plane_z = z;
  }
  return choice;
}

vg::GroundMade make_ground(vg::Mesh& mesh, const vg::GroundRequest& request) {
  try {
    return vg::add_ground(mesh, request);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) +
                                ". Give the ground another way: --terrain DEM, --ground-plane Z (a plane at Z m), or "
                                "--ground-plane auto (inferred from the building bases)");
  }
}

vg::gis::CityOptions city_options(const CityArguments& a, const vg::SceneFileOptions& file, bool nodes_given) {
  vg::gis::CityOptions o;
  o.file = file;
  o.footprints.height_field = a.height_field;
  o.footprints.levels_field = a.levels_field;
  o.footprints.storey_height = a.storey_height;
  o.footprints.strict = a.strict;
  o.terrain = a.terrain;
  // Footprints without z or a DEM stand on the plane the user names.
  const GroundPlaneChoice ground = ground_plane_choice(a, 1.7);
  if (ground.request.rule == vg::GroundRule::plane_at) o.plane_z = ground.request.plane_z;
  o.max_terrain_cells = a.allow_large ? 0.0 : vg::gis::kDefaultMaxTerrainCells;
  o.refuse_exposed_gaps = !nodes_given;
  return o;
}

}  // namespace attenuvis::cli
