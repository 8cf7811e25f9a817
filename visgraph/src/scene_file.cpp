// Scene files by content (scene_file.hpp).
#include <attenuvis/visgraph/detail/gltf.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/obj.hpp>
#include <attenuvis/visgraph/scene_file.hpp>

#include <attenuvis/io/input_file.hpp>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace attenuvis::visgraph {

UpAxis parse_up_axis(const std::string& text) {
  if (text == "z" || text == "Z") return UpAxis::z;
  if (text == "y" || text == "Y") return UpAxis::y;
  throw std::invalid_argument("up axis: expected z or y, got '" + text + "'");
}

namespace {

// (x, y, z) -> (x, -z, y): a y-up model turned z-up (right-handed both).
void turn_y_up_to_z_up(Mesh& mesh) {
  for (Eigen::Vector3d& v : mesh.vertices) v = Eigen::Vector3d(v.x(), -v.z(), v.y());
}

// A warning when the mesh (already in attenuvis's z-up frame) looks like a
// model of the other convention read as it was: its vertical extent is not
// its smallest one and a horizontal axis is less than half as long, as a city
// exported y-up and read z-up would be.  Empty when the frame looks right.
std::string up_axis_warning(const Mesh& mesh, const std::string& how_to_fix) {
  const MeshStats stats = mesh_stats(mesh);
  const Eigen::Vector3d extent = stats.upper - stats.lower;
  const double horizontal_min = std::min(extent.x(), extent.y());
  if (!(extent.z() > 0) || !(horizontal_min < 0.5 * extent.z())) return "";
  const char axis = extent.x() < extent.y() ? 'x' : 'y';
  return std::string("the scene is ") + std::to_string(static_cast<long>(extent.z())) + " m tall but only " +
         std::to_string(static_cast<long>(horizontal_min)) + " m along " + axis +
         ": it looks like a model of the other up-axis convention (" + how_to_fix + ")";
}

// What kind of GIS vector layer the file's first bytes show, or "" for none:
// such a file holds footprints, not a scene, and the OBJ reader would only
// report a syntax error.
std::string vector_layer_kind(const std::string& head) {
  if (head.compare(0, 16, std::string("SQLite format 3\0", 16)) == 0) return "a GeoPackage (SQLite) file";
  if (head.size() >= 4 && head.compare(0, 4, std::string("\x00\x00\x27\x0a", 4)) == 0) return "a Shapefile";
  const auto brace = head.find_first_not_of(" \t\r\n");
  if (brace != std::string::npos && head[brace] == '{' &&
      (head.find("\"FeatureCollection\"") != std::string::npos || head.find("\"Feature\"") != std::string::npos))
    return "GeoJSON";
  return "";
}

}  // namespace

SceneFile load_scene_file(const std::string& path, const SceneFileOptions& options) {
  // A device or FIFO (/dev/zero, /dev/urandom) would be read for ever: only
  // regular files up to kMaxSceneFileBytes are scenes.
  io::require_readable_input(path, kMaxSceneFileBytes);
  std::string head(65536, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  SceneFile file;
  if (!options.lod.empty() && !looks_like_cityjson(head))
    throw std::invalid_argument(path + ": --lod applies to CityJSON files only");
  if (looks_like_gltf(head)) {
    file.mesh = load_gltf(path);
    file.format = "glTF";
  } else if (looks_like_cityjson(head)) {
    CityJsonOptions o;
    o.lod = options.lod;
    CityJsonReport report;
    file.mesh = load_cityjson(path, o, &report);
    file.format = "CityJSON " + report.version;
    if (report.degenerate_surfaces)
      file.warnings.push_back(std::to_string(report.degenerate_surfaces) + " of " + std::to_string(report.surfaces) +
                              " surfaces have zero area and were skipped");
    if (report.invalid_surfaces)
      file.warnings.push_back(std::to_string(report.invalid_surfaces) +
                              " surfaces are self-intersecting and were triangulated in part");
  } else if (const std::string kind = vector_layer_kind(head); !kind.empty()) {
    throw std::invalid_argument(path + " is " + kind + " of GIS features, not a scene: footprints are extruded "
                                "by a height field (attenuvis vg --height-field NAME, or --levels-field; "
                                "Python: Scene.from_footprints)");
  } else {
    file.mesh = load_obj(path);
    file.format = "OBJ";
    if (options.obj_up_axis == UpAxis::y) turn_y_up_to_z_up(file.mesh);
    const std::string w = up_axis_warning(
        file.mesh, options.obj_up_axis == UpAxis::z ? "read as z-up; --up-axis y if it was exported y-up"
                                                    : "read as y-up by --up-axis y; leave it out if the file is z-up");
    if (!w.empty()) file.warnings.push_back(w);
  }
  return file;
}

}  // namespace attenuvis::visgraph
