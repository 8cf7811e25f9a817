// GeoJSON writer and point reader (geojson.hpp), on nlohmann-json.
#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/geojson.hpp>
#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/input_file.hpp>

#include <attenuvis/io/staged_file.hpp>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {
using json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& path, const std::string& where, const std::string& what) {
  throw std::runtime_error(path + (where.empty() ? "" : ": " + where) + ": " + what);
}

std::string line_and_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

Eigen::Vector3d point(const json& c, const std::string& path, const std::string& where) {
  if (!c.is_array() || c.size() < 2 || !c[0].is_number() || !c[1].is_number())
    fail(path, where, "a position must be [x, y, z] numbers");
  if (c.size() < 3 || !c[2].is_number())
    fail(path, where, "the point has no z: nodes are eye positions and need x, y and z (metres)");
  const Eigen::Vector3d p(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
  if (!p.allFinite()) fail(path, where, "coordinate is not finite");
  for (int k = 0; k < 3; ++k) check_coordinate(p[k], path + ": " + where);
  return p;
}

void read_geometry(const json& g, const std::string& path, const std::string& where, std::vector<Eigen::Vector3d>& out) {
  if (!g.is_object() || !g.contains("type") || !g["type"].is_string()) fail(path, where, "a geometry needs a type");
  const std::string type = g["type"].get<std::string>();
  const json& c = g.contains("coordinates") ? g["coordinates"] : json();
  if (type == "Point") {
    out.push_back(point(c, path, where));
  } else if (type == "MultiPoint") {
    if (!c.is_array()) fail(path, where, "MultiPoint coordinates must be an array");
    for (std::size_t k = 0; k < c.size(); ++k) out.push_back(point(c[k], path, where + " point " + std::to_string(k)));
  } else {
    fail(path, where, "is a " + type + ": nodes must be Point or MultiPoint geometries");
  }
}
}  // namespace

std::string geojson_crs_name(const std::string& crs) {
  const std::string s = short_crs_name(crs);
  if (s.compare(0, 5, "EPSG:") == 0) return "urn:ogc:def:crs:EPSG::" + s.substr(5);
  return s;
}

std::string geojson_text(const ScoreTable& table, const std::string& crs) {
  const std::vector<std::string> columns = score_columns(table);
  std::vector<std::vector<double>> values;
  for (std::size_t c = 3; c < columns.size(); ++c) values.push_back(score_values(table, columns[c]));
  json doc;
  doc["type"] = "FeatureCollection";
  doc["name"] = "attenuvis visibility graph nodes";
  if (!crs.empty()) doc["crs"] = {{"type", "name"}, {"properties", {{"name", geojson_crs_name(crs)}}}};
  json features = json::array();
  for (std::size_t i = 0; i < table.result->nodes; ++i) {
    const Eigen::Vector3d& p = (*table.eyes)[i];
    json properties;
    properties["node"] = i;
    for (std::size_t c = 3; c < columns.size(); ++c) {
      const double v = values[c - 3][i];
      properties[columns[c]] = std::isfinite(v) ? json(v) : json(nullptr);
    }
    features.push_back({{"type", "Feature"},
                        {"geometry", {{"type", "Point"}, {"coordinates", {p.x(), p.y(), p.z()}}}},
                        {"properties", std::move(properties)}});
  }
  doc["features"] = std::move(features);
  return doc.dump() + "\n";
}

void write_geojson(const std::string& path, const ScoreTable& table, const std::string& crs) {
  io::write_file_atomically(path, geojson_text(table, crs));
}

GeoJsonPoints read_geojson_points(const std::string& path) {
  const std::string text = io::read_input_file(path, kMaxNodeFileBytes);
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    fail(path, line_and_column(text, e.byte), "not valid JSON");
  } catch (const json::exception& e) {
    // out_of_range: a number too large for any JSON number type (1e400).
    fail(path, "", std::string("not readable JSON: ") + e.what());
  }
  GeoJsonPoints out;
  if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string()) fail(path, "", "not a GeoJSON object (no type)");
  if (doc.contains("crs") && doc["crs"].is_object() && doc["crs"].contains("properties") &&
      doc["crs"]["properties"].is_object() && doc["crs"]["properties"].contains("name") &&
      doc["crs"]["properties"]["name"].is_string())
    out.crs = doc["crs"]["properties"]["name"].get<std::string>();
  const std::string type = doc["type"].get<std::string>();
  if (type == "FeatureCollection") {
    if (!doc.contains("features") || !doc["features"].is_array()) fail(path, "", "a FeatureCollection needs a features array");
    const json& features = doc["features"];
    for (std::size_t f = 0; f < features.size(); ++f) {
      const std::string where = "feature " + std::to_string(f);
      if (!features[f].is_object() || !features[f].contains("geometry")) fail(path, where, "a feature needs a geometry");
      read_geometry(features[f]["geometry"], path, where, out.points);
    }
  } else if (type == "Feature") {
    if (!doc.contains("geometry")) fail(path, "feature", "a feature needs a geometry");
    read_geometry(doc["geometry"], path, "feature", out.points);
  } else {
    read_geometry(doc, path, "geometry", out.points);
  }
  if (out.points.empty()) fail(path, "", "holds no points");
  return out;
}

}  // namespace attenuvis::visgraph
