// Scene files, recognised by content whatever they are called: CityJSON
// (.json, .city.json, .jsonl), glTF (.gltf, .glb), or else OBJ.
#pragma once

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/mesh.hpp>

#include <string>
#include <vector>

namespace attenuvis::visgraph {

// The up axis of an OBJ file: z (attenuvis, GIS, CityJSON) or y (most 3D
// tools' default export).  CityJSON is z-up and glTF y-up by definition.
enum class UpAxis { z, y };

// Parses "z" or "y"; throws std::invalid_argument otherwise.
UpAxis parse_up_axis(const std::string& text);

// How a scene file is read.
struct SceneFileOptions {
  UpAxis obj_up_axis = UpAxis::z;
  std::string lod;  // CityJSON level of detail (cityjson.hpp)
};

// A scene file read: its mesh, what it was and what the reader warned about.
struct SceneFile {
  Mesh mesh;                          // z up
  std::string format;                 // "CityJSON 2.0", "CityJSONSeq 2.0", "glTF", "OBJ"
  std::vector<std::string> warnings;  // e.g. the up axis looks wrong, faces skipped
};

// An OBJ file read with obj_up_axis y is turned z-up, (x, y, z) -> (x, -z,
// y); either way `warnings` says when its extents look like the other
// convention's (a vertical extent that is not its smallest and a horizontal
// axis less than half as long, as a city exported y-up and read z-up).
// A GeoPackage, Shapefile or GeoJSON file is refused with
// std::invalid_argument saying that footprints need a height field
// (visgraph/gis/city.hpp reads them).
SceneFile load_scene_file(const std::string& path, const SceneFileOptions& options = {});

}  // namespace attenuvis::visgraph
