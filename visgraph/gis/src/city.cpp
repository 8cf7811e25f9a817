// City models from scene files or footprints, on a DEM (city.hpp).
#include <attenuvis/visgraph/gis/city.hpp>

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/footprints.hpp>
#include <attenuvis/visgraph/scene.hpp>

#include <attenuvis/io/number_text.hpp>

#include <stdexcept>

namespace attenuvis::visgraph::gis {

namespace {

struct Extent {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
};

void footprint_warnings(const std::string& path, const FootprintLayer& layer, const FootprintFields& fields,
                        std::vector<std::string>& warnings) {
  if (layer.layers > 1)
    warnings.push_back(path + " holds " + std::to_string(layer.layers) + " layers: the first, '" + layer.layer +
                       "', was read");
  if (layer.skipped) {
    std::string names = fields.height_field;
    if (!fields.levels_field.empty()) names += (names.empty() ? "" : " or ") + fields.levels_field;
    warnings.push_back(std::to_string(layer.skipped) + " of " + std::to_string(layer.features) +
                       " features have no usable height (" + names + ") and were skipped; the first, " +
                       layer.first_skipped + " (--strict refuses them)");
  }
  if (layer.crs.empty())
    warnings.push_back(path + " names no CRS: its coordinates are taken as metres in a local frame");
}

// Reads the DEM around `extent`, in the model's CRS, into `city`.
Dem read_terrain(const CityOptions& options, const Extent& extent, CityModel& city) {
  DemRequest request;
  request.min_x = extent.min_x;
  request.min_y = extent.min_y;
  request.max_x = extent.max_x;
  request.max_y = extent.max_y;
  request.max_cells = options.max_terrain_cells;
  request.model_crs = city.mesh.crs;
  Dem dem = read_dem(options.terrain, request);
  if (city.mesh.crs.empty() && !dem.crs.empty()) {
    city.warnings.push_back("the model names no CRS: it is taken to be the DEM's, " + dem.crs_label);
    city.mesh.crs = dem.crs;
  } else if (dem.crs.empty() && !city.mesh.crs.empty()) {
    city.warnings.push_back(options.terrain + " names no CRS: it is taken to be the model's, " +
                            short_crs_name(city.mesh.crs));
  }
  return dem;
}

}  // namespace

CityModel load_city(const std::string& path, const CityOptions& options) {
  CityModel city;
  std::optional<FootprintLayer> layer;
  Extent extent;
  if (options.footprints.wanted()) {
    layer = read_footprints(path, options.footprints);
    footprint_warnings(path, *layer, options.footprints, city.warnings);
    city.mesh.crs = layer->crs;
    extent = {layer->min_x, layer->min_y, layer->max_x, layer->max_y};
    city.format = "footprints (layer '" + layer->layer + "', " + std::to_string(layer->footprints.size()) + " of " +
                  std::to_string(layer->features) + " features extruded)";
  } else {
    SceneFile file = load_scene_file(path, options.file);
    city.mesh = std::move(file.mesh);
    city.format = file.format;
    for (const std::string& w : file.warnings) city.warnings.push_back(path + ": " + w);
    const MeshStats stats = mesh_stats(city.mesh);
    extent = {stats.lower.x(), stats.lower.y(), stats.upper.x(), stats.upper.y()};
  }
  std::optional<Dem> dem;
  if (!options.terrain.empty()) dem = read_terrain(options, extent, city);
  if (layer) {
    FootprintGround ground;
    ground.terrain = dem ? &dem->grid : nullptr;
    ground.vertex_z = layer->vertex_z;
    ground.plane_z = options.plane_z;
    const std::string crs = city.mesh.crs;
    city.mesh = extrude_footprints(layer->footprints, ground, path);
    city.mesh.crs = crs;
  }
  if (!dem) return city;
  if (options.refuse_exposed_gaps) {
    bool gaps = false;
    for (double z : dem->grid.z) gaps = gaps || std::isnan(z);
    if (gaps) {
      const Scene buildings(city.mesh);
      const std::string cell = exposed_missing_cell(dem->grid, buildings);
      if (!cell.empty())
        throw std::invalid_argument(options.terrain + " has no data at " + cell +
                                    ", where nodes would stand (no building stands over it): fill it, e.g. "
                                    "gdal_fillnodata.py, or give the nodes (--nodes) away from it");
    }
  }
  add_terrain(city.mesh, dem->grid);
  city.terrain = std::move(dem->grid);
  city.terrain_source = options.terrain;
  city.ground = "a DEM, " + dem->description;
  return city;
}

}  // namespace attenuvis::visgraph::gis
