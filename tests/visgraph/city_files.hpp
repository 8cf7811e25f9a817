// City models written by the tests themselves: a Mesh as a CityJSON 1.0 file
// (one Building per group, one MultiSurface of its triangles with their
// classes as semantic surfaces; vertices as given, no transform, so that the
// reader gets the same doubles back).
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace vgtest {

inline void write_cityjson(const std::string& path, const attenuvis::visgraph::Mesh& mesh, const std::string& crs = "") {
  using nlohmann::json;
  json doc = {{"type", "CityJSON"}, {"version", "1.0"}, {"CityObjects", json::object()}};
  if (!crs.empty()) doc["metadata"] = {{"referenceSystem", crs}};
  json vertices = json::array();
  for (const auto& v : mesh.vertices) vertices.push_back({v.x(), v.y(), v.z()});
  doc["vertices"] = vertices;
  std::vector<json> boundaries(mesh.groups.size(), json::array()), values(mesh.groups.size(), json::array());
  const bool classed = mesh.triangle_class.size() == mesh.triangles.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto g = mesh.triangle_group[t];
    const auto& tri = mesh.triangles[t];
    boundaries[g].push_back(json::array({json::array({tri[0], tri[1], tri[2]})}));
    values[g].push_back(classed ? json(mesh.triangle_class[t]) : json(nullptr));
  }
  json surfaces = json::array();
  for (const std::string& c : mesh.classes) surfaces.push_back({{"type", c}});
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    json geometry = {{"type", "MultiSurface"}, {"lod", 2}, {"boundaries", boundaries[g]}};
    if (classed) geometry["semantics"] = {{"surfaces", surfaces}, {"values", values[g]}};
    doc["CityObjects"][mesh.groups[g]] = {{"type", "Building"}, {"geometry", json::array({geometry})}};
  }
  std::ofstream(path) << doc.dump();
}

}  // namespace vgtest
