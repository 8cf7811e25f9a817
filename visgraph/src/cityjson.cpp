// CityJSON reader (cityjson.hpp), on nlohmann-json.
//
// Boundaries nest by geometry type (CityJSON 2.0 spec, "Geometry Objects"):
//   MultiSurface, CompositeSurface:  [surface][ring][vertex]
//   Solid:                           [shell][surface][ring][vertex]
//   MultiSolid, CompositeSolid:      [solid][shell][surface][ring][vertex]
// and semantics.values nests the same way without the ring and vertex levels
// (an integer into semantics.surfaces, or null).
#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/detail/polygon.hpp>

#include <attenuvis/io/input_file.hpp>
#include <attenuvis/io/number_text.hpp>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace attenuvis::visgraph {

namespace {

using json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& path, const std::string& where, const std::string& what) {
  throw std::runtime_error(path + (where.empty() ? "" : ": " + where) + ": " + what);
}

std::string read_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "", "is a directory, not a CityJSON file");
  if (!std::filesystem::exists(path, ec)) fail(path, "", "cannot open: " + (ec ? ec.message() : "no such file"));
  return io::read_input_file(path, kMaxSceneFileBytes);
}

// "line L, column C" of a byte offset (1-based), for syntax errors.
std::string position_of(const std::string& text, std::size_t byte, std::size_t first_line = 1) {
  byte = std::min(byte, text.size());
  std::size_t line = first_line, column = 1;
  for (std::size_t i = 0; i + 1 < byte; ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
  return "byte " + std::to_string(byte) + " (line " + std::to_string(line) + ", column " + std::to_string(column) + ")";
}

json parse_json(const std::string& path, const std::string& text, std::size_t first_line = 1) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const auto colon = what.rfind(": ");  // nlohmann: "[json.exception.parse_error.101] parse error at ...: WHY"
    fail(path, position_of(text, e.byte, first_line), "not valid JSON: " + what.substr(colon == std::string::npos ? 0 : colon + 2));
  }
}

std::string lod_text(const json& lod) {
  if (lod.is_string()) return lod.get<std::string>();
  if (lod.is_number()) return io::shortest(lod.get<double>());
  return "";
}

double lod_value(const std::string& lod) {
  try {
    return io::parse_double(lod, "lod");
  } catch (const std::exception&) {
    return -1;
  }
}

int nesting_of(const std::string& type) {
  if (type == "MultiSurface" || type == "CompositeSurface") return 3;
  if (type == "Solid") return 4;
  if (type == "MultiSolid" || type == "CompositeSolid") return 5;
  return 0;
}

class Reader {
 public:
  Reader(std::string path, const CityJsonOptions& options) : path_(std::move(path)), options_(options) {}

  // The CityJSON object (or the first line of a CityJSONSeq): version,
  // transform, CRS, templates.
  void read_header(const json& doc) {
    if (!doc.is_object() || doc.value("type", "") != "CityJSON") fail(path_, "", "not a CityJSON file (no \"type\": \"CityJSON\")");
    report_.version = doc.value("version", "");
    if (report_.version != "1.0" && report_.version != "1.1" && report_.version != "2.0")
      fail(path_, "version", "CityJSON version '" + report_.version + "' is not supported (1.0, 1.1, 2.0)");
    if (doc.contains("transform")) {
      const json& t = doc["transform"];
      scale_ = vector3(t, "scale", "transform");
      translate_ = vector3(t, "translate", "transform");
    }
    if (doc.contains("metadata") && doc["metadata"].is_object()) {
      const json& rs = doc["metadata"].value("referenceSystem", json());
      if (rs.is_string()) mesh_.crs = rs.get<std::string>();
    }
    if (doc.contains("geometry-templates")) {
      const json& gt = doc["geometry-templates"];
      templates_ = gt.value("templates", json::array());
      for (const json& v : gt.value("vertices-templates", json::array())) template_vertices_.push_back(raw_vector(v, "geometry-templates/vertices-templates"));
    }
  }

  // CityObjects and vertices of a CityJSON document or a CityJSONFeature.
  void read_objects(const json& doc, const std::string& where) {
    const std::size_t base = mesh_.vertices.size();
    const json& vertices = doc.value("vertices", json::array());
    if (!vertices.is_array()) fail(path_, where + "vertices", "is not an array");
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const Eigen::Vector3d v = raw_vector(vertices[i], where + "vertices/" + std::to_string(i));
      mesh_.vertices.push_back(v.cwiseProduct(scale_) + translate_);
      for (int c = 0; c < 3; ++c)
        check_coordinate(mesh_.vertices.back()[c], path_ + ": " + where + "vertices/" + std::to_string(i));
    }
    vertex_base_ = base;
    vertex_count_ = vertices.size();
    const json& objects = doc.value("CityObjects", json::object());
    if (!objects.is_object()) fail(path_, where + "CityObjects", "is not an object");
    for (const auto& [id, object] : objects.items()) read_object(id, object, where + "CityObjects/" + id);
  }

  Mesh finish() {
    if (mesh_.triangles.empty())
      fail(path_, "", "no triangles (" + std::to_string(report_.city_objects) + " city objects, " +
                          std::to_string(report_.objects_read) + " with geometry" +
                          (options_.lod.empty() ? "" : " at LoD " + options_.lod) + ")");
    report_.triangles = mesh_.triangles.size();
    return std::move(mesh_);
  }
  const CityJsonReport& report() const { return report_; }

 private:
  Eigen::Vector3d raw_vector(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      fail(path_, where, "expected [x, y, z] numbers");
    return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
  }
  Eigen::Vector3d vector3(const json& parent, const char* key, const std::string& where) const {
    if (!parent.is_object() || !parent.contains(key)) fail(path_, where, std::string("missing '") + key + "'");
    return raw_vector(parent[key], where + "/" + key);
  }

  void read_object(const std::string& id, const json& object, const std::string& where) {
    ++report_.city_objects;
    if (!object.is_object()) fail(path_, where, "a city object must be a JSON object");
    const std::string type = object.value("type", "");
    const json& geometries = object.value("geometry", json::array());
    if (!geometries.is_array()) fail(path_, where + "/geometry", "is not an array");
    // The geometry to read: the one at the requested LoD, else the highest.
    std::ptrdiff_t chosen = -1;
    double best = -2;
    for (std::size_t g = 0; g < geometries.size(); ++g) {
      const json& geometry = geometries[g];
      if (!geometry.is_object()) fail(path_, where + "/geometry/" + std::to_string(g), "is not an object");
      const std::string lod = geometry_lod(geometry);
      if (!options_.lod.empty()) {
        if (lod == options_.lod || lod_value(lod) == lod_value(options_.lod)) chosen = static_cast<std::ptrdiff_t>(g);
      } else if (lod_value(lod) > best) {
        best = lod_value(lod);
        chosen = static_cast<std::ptrdiff_t>(g);
      }
    }
    if (chosen < 0) return;
    ++report_.objects_read;
    const auto group = static_cast<std::uint32_t>(mesh_.groups.size());
    mesh_.groups.push_back(id);
    read_geometry(geometries[static_cast<std::size_t>(chosen)], type, group,
                  where + "/geometry/" + std::to_string(chosen));
  }

  std::string geometry_lod(const json& geometry) const {
    if (geometry.value("type", "") == "GeometryInstance") {
      const json& t = geometry.value("template", json());
      if (t.is_number_unsigned() && t.get<std::size_t>() < templates_.size())
        return lod_text(templates_[t.get<std::size_t>()].value("lod", json()));
      return "";
    }
    return lod_text(geometry.value("lod", json()));
  }

  void read_geometry(const json& geometry, const std::string& object_type, std::uint32_t group,
                     const std::string& where) {
    const std::string type = geometry.value("type", "");
    if (type == "GeometryInstance") return read_instance(geometry, object_type, group, where);
    const int nesting = nesting_of(type);
    if (nesting == 0) return;  // points and lines have no surfaces
    Placement place;
    place.base = vertex_base_;
    place.count = vertex_count_;
    read_boundaries(geometry, object_type, group, nesting, place, where);
  }

  // Where a geometry's vertex indices point: mesh_.vertices[base + i], i < count.
  struct Placement {
    std::size_t base = 0, count = 0;
  };

  void read_instance(const json& geometry, const std::string& object_type, std::uint32_t group,
                     const std::string& where) {
    const json& t = geometry.value("template", json());
    if (!t.is_number_unsigned() || t.get<std::size_t>() >= templates_.size())
      fail(path_, where + "/template", "no such geometry template (" + std::to_string(templates_.size()) + " in the file)");
    const json& b = geometry.value("boundaries", json());
    if (!b.is_array() || b.size() != 1 || !b[0].is_number_unsigned() || b[0].get<std::size_t>() >= vertex_count_)
      fail(path_, where + "/boundaries", "a GeometryInstance needs one reference-point vertex index");
    const Eigen::Vector3d reference = mesh_.vertices[vertex_base_ + b[0].get<std::size_t>()];
    const json& m = geometry.value("transformationMatrix", json());
    if (!m.is_array() || m.size() != 16) fail(path_, where + "/transformationMatrix", "expected 16 numbers");
    Eigen::Matrix4d matrix;
    for (int k = 0; k < 16; ++k) {
      if (!m[static_cast<std::size_t>(k)].is_number()) fail(path_, where + "/transformationMatrix", "expected 16 numbers");
      matrix(k / 4, k % 4) = m[static_cast<std::size_t>(k)].get<double>();  // row-major
    }
    // The template's vertices, transformed and moved to the reference point.
    Placement place;
    place.base = mesh_.vertices.size();
    place.count = template_vertices_.size();
    for (const Eigen::Vector3d& v : template_vertices_) {
      mesh_.vertices.push_back(reference + (matrix * v.homogeneous()).head<3>());
      for (int c = 0; c < 3; ++c) check_coordinate(mesh_.vertices.back()[c], path_ + ": " + where + " (template vertex)");
    }
    const json& templ = templates_[t.get<std::size_t>()];
    const int nesting = nesting_of(templ.value("type", ""));
    if (nesting == 0) return;
    read_boundaries(templ, object_type, group, nesting, place, where + " (template " + std::to_string(t.get<std::size_t>()) + ")");
  }

  void read_boundaries(const json& geometry, const std::string& object_type, std::uint32_t group, int nesting,
                       const Placement& place, const std::string& where) {
    const json& boundaries = geometry.value("boundaries", json());
    if (!boundaries.is_array()) fail(path_, where + "/boundaries", "is not an array");
    const json& semantics = geometry.value("semantics", json());
    const json surfaces = semantics.is_object() ? semantics.value("surfaces", json::array()) : json::array();
    const json values = semantics.is_object() ? semantics.value("values", json()) : json();
    walk(boundaries, values, surfaces, nesting, object_type, group, place, where + "/boundaries");
  }

  // Descends `nesting` - 2 levels to the surfaces, carrying the matching
  // semantics value along.
  void walk(const json& b, const json& values, const json& surfaces, int nesting, const std::string& object_type,
            std::uint32_t group, const Placement& place, const std::string& where) {
    if (!b.is_array()) fail(path_, where, "is not an array");
    if (nesting == 2) return read_surface(b, values, surfaces, object_type, group, place, where);
    for (std::size_t i = 0; i < b.size(); ++i) {
      const json& v = values.is_array() && i < values.size() ? values[i] : json();
      walk(b[i], v, surfaces, nesting - 1, object_type, group, place, where + "/" + std::to_string(i));
    }
  }

  void read_surface(const json& rings, const json& value, const json& surfaces, const std::string& object_type,
                    std::uint32_t group, const Placement& place, const std::string& where) {
    ++report_.surfaces;
    std::vector<std::vector<Eigen::Vector3d>> points;
    std::vector<std::size_t> ids;  // mesh vertex of each concatenated ring position
    for (std::size_t r = 0; r < rings.size(); ++r) {
      const json& ring = rings[r];
      if (!ring.is_array()) fail(path_, where + "/" + std::to_string(r), "a ring must be an array of vertex indices");
      points.emplace_back();
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const json& index = ring[k];
        if (!index.is_number_unsigned() || index.get<std::size_t>() >= place.count)
          fail(path_, where + "/" + std::to_string(r) + "/" + std::to_string(k),
               "vertex index " + index.dump() + " is out of range (" + std::to_string(place.count) + " vertices)");
        const std::size_t id = place.base + index.get<std::size_t>();
        points.back().push_back(mesh_.vertices[id]);
        ids.push_back(id);
      }
    }
    // Ear clipping is quadratic in the vertices: a 100,000-vertex surface would take minutes.
    if (ids.size() > kMaxPolygonVertices)
      fail(path_, where, "surface has " + std::to_string(ids.size()) + " vertices, more than the " +
                             std::to_string(kMaxPolygonVertices) + " a surface may have: split it");
    const PolygonTriangles result = triangulate_polygon(points);
    if (result.status == PolygonStatus::degenerate) ++report_.degenerate_surfaces;
    if (result.status == PolygonStatus::partial) ++report_.invalid_surfaces;
    if (result.triangles.empty()) return;
    std::string cls = object_type;
    if (value.is_number_unsigned() && value.get<std::size_t>() < surfaces.size()) {
      const json& s = surfaces[value.get<std::size_t>()];
      if (s.is_object() && s.contains("type") && s["type"].is_string()) cls = s["type"].get<std::string>();
    }
    const auto class_index = static_cast<std::uint32_t>(class_index_of(cls));
    for (const auto& t : result.triangles) {
      mesh_.triangles.push_back({static_cast<std::uint32_t>(ids[t[0]]), static_cast<std::uint32_t>(ids[t[1]]),
                                 static_cast<std::uint32_t>(ids[t[2]])});
      mesh_.triangle_group.push_back(group);
      mesh_.triangle_class.push_back(class_index);
    }
  }

  std::size_t class_index_of(const std::string& name) {
    const auto it = class_index_.find(name);
    if (it != class_index_.end()) return it->second;
    mesh_.classes.push_back(name);
    return class_index_[name] = mesh_.classes.size() - 1;
  }

  std::string path_;
  CityJsonOptions options_;
  Mesh mesh_;
  CityJsonReport report_;
  Eigen::Vector3d scale_{1, 1, 1}, translate_{0, 0, 0};
  json templates_ = json::array();
  std::vector<Eigen::Vector3d> template_vertices_;
  std::size_t vertex_base_ = 0, vertex_count_ = 0;
  std::unordered_map<std::string, std::size_t> class_index_;
};

// CityJSONSeq: the first line is a CityJSON object (transform, CRS), each
// further line a CityJSONFeature with its own vertices.
bool is_sequence(const std::string& text) {
  const auto newline = text.find('\n');
  if (newline == std::string::npos) return false;
  return text.find_first_not_of(" \t\r\n", newline) != std::string::npos &&
         text.find("\"CityJSONFeature\"") != std::string::npos && text.compare(0, 1, "{") == 0 &&
         text.rfind('}', newline) != std::string::npos && json::accept(text.substr(0, newline));
}

Mesh read_cityjson(const std::string& path, const CityJsonOptions& options, CityJsonReport* report);

}  // namespace

bool looks_like_cityjson(const std::string& head) {
  return head.find("\"CityJSON\"") != std::string::npos || head.find("\"CityObjects\"") != std::string::npos ||
         head.find("\"CityJSONFeature\"") != std::string::npos;
}

Mesh load_cityjson(const std::string& path, const CityJsonOptions& options, CityJsonReport* report) {
  try {
    return read_cityjson(path, options, report);
  } catch (const nlohmann::ordered_json::exception& e) {
    // A member of the wrong JSON type where the reader did not check it.
    throw std::runtime_error(path + ": unexpected CityJSON structure: " + std::string(e.what()));
  }
}

namespace {
Mesh read_cityjson(const std::string& path, const CityJsonOptions& options, CityJsonReport* report) {
  const std::string text = read_text(path);
  Reader reader(path, options);
  if (is_sequence(text)) {
    std::size_t start = 0, line = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      ++line;
      const std::string row = text.substr(start, end - start);
      start = end + 1;
      if (row.find_first_not_of(" \t\r") == std::string::npos) continue;
      const json doc = parse_json(path, row, line);
      if (line == 1) {
        reader.read_header(doc);
        reader.read_objects(doc, "line 1: ");
      } else {
        if (!doc.is_object() || doc.value("type", "") != "CityJSONFeature")
          fail(path, "line " + std::to_string(line), "expected a CityJSONFeature");
        reader.read_objects(doc, "line " + std::to_string(line) + ": ");
      }
    }
  } else {
    const json doc = parse_json(path, text);
    reader.read_header(doc);
    reader.read_objects(doc, "");
  }
  Mesh mesh = reader.finish();
  if (report) *report = reader.report();
  return mesh;
}
}  // namespace

std::string short_crs_name(const std::string& crs) {
  for (const std::string prefix : {"urn:ogc:def:crs:EPSG::", "urn:ogc:def:crs:EPSG:", "https://www.opengis.net/def/crs/EPSG/0/",
                                   "http://www.opengis.net/def/crs/EPSG/0/"}) {
    if (crs.compare(0, prefix.size(), prefix) == 0) return "EPSG:" + crs.substr(prefix.size());
  }
  return crs;
}

}  // namespace attenuvis::visgraph
