// A city model as the visibility graph takes it, from what cities publish: a
// scene file (CityJSON, glTF, OBJ) or a layer of footprints with heights,
// optionally standing on a DEM.  What the command line and the Python
// package both call; every check that can refuse the input runs here, before
// any node is placed.
#pragma once

#include <attenuvis/visgraph/gis/dem.hpp>
#include <attenuvis/visgraph/gis/footprint_layer.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/scene_file.hpp>
#include <attenuvis/visgraph/terrain.hpp>

#include <optional>
#include <string>
#include <vector>

namespace attenuvis::visgraph::gis {

struct CityOptions {
  SceneFileOptions file;         // for a scene file
  FootprintFields footprints;    // wanted(): the file is a footprint layer
  std::string terrain;           // a DEM to stand on, or ""
  double plane_z = 0;            // m: footprints without z or a DEM stand on this plane
  double max_terrain_cells = kDefaultMaxTerrainCells;  // 0 = no limit
  // Refuse DEM cells without data that no building stands over (nodes of a
  // grid may stand there).  Off when the nodes are given: then
  // check_nodes_on_terrain (terrain.hpp) checks the DEM under each of them.
  bool refuse_exposed_gaps = true;
};

struct CityModel {
  Mesh mesh;                          // the buildings (and the DEM's surface, when given)
  std::string format;                 // "CityJSON 2.0", ..., "footprints (GPKG layer 'buildings')"
  std::vector<std::string> warnings;  // what the readers noticed
  std::optional<HeightGrid> terrain;  // the DEM window, when one was given
  std::string terrain_source;         // the DEM's path
  std::string ground;                 // "a DEM: ..." when one was given, else ""
};

// Reads the model and its DEM.  Throws (std::invalid_argument,
// std::runtime_error) with what the readers say (scene_file.hpp,
// footprint_layer.hpp, dem.hpp, footprints.hpp), and for a DEM cell without
// data that no building stands over (refuse_exposed_gaps).
CityModel load_city(const std::string& path, const CityOptions& options);

}  // namespace attenuvis::visgraph::gis
