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

struct SceneFileOptions {
  UpAxis obj_up_axis = UpAxis::z;
  std::string lod;  // CityJSON level of detail (cityjson.hpp)
};

struct SceneFile {
  Mesh mesh;                          // z up
  std::string format;                 // "CityJSON 2.0", "CityJSONSeq 2.0", "glTF", "OBJ"
  std::vector<std::string> warnings;  // e.g. the up axis looks wrong, faces skipped
};

SceneFile load_scene_file(const std::string& path, const SceneFileOptions& options = {});

// (x, y, z) -> (x, -z, y): a y-up model turned z-up (right-handed both).
void turn_y_up_to_z_up(Mesh& mesh);

// A warning when the mesh (already in attenuvis's z-up frame) looks like a
// model of the other convention read as it was: its vertical extent is not
// its smallest one and a horizontal axis is less than half as long, as a city
// exported y-up and read z-up would be.  Empty when the frame looks right.
std::string up_axis_warning(const Mesh& mesh, const std::string& how_to_fix);

}  // namespace attenuvis::visgraph
