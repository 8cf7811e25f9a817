// GeoJSON node layer (visgraph/src/geojson.cpp): written with the scene's CRS
// and every score as a property, read back as node positions; malformed
// point files give errors naming file and feature.
#include <attenuvis/visgraph/geojson.hpp>
#include <attenuvis/visgraph/nodes.hpp>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

namespace vg = attenuvis::visgraph;
using Eigen::Vector3d;

namespace {
std::string temp_path(const std::string& name) { return "/tmp/attenuvis_test_geojson_" + name; }
void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
std::string read_error(const std::string& path) {
  try {
    vg::read_nodes(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("GeoJSON: nodes with every score and the scene's CRS, read back exactly", "[visgraph][geojson]") {
  const std::vector<Vector3d> eyes = {{92000.125, 436000.5, 1.7}, {92010.0, 436001.25, 3.2}};
  vg::VisibilityResult r;
  r.nodes = 2;
  r.degree = {1, 0};
  r.sum = {{0.5, 0.0}};
  vg::ScoreTable table;
  table.eyes = &eyes;
  table.result = &r;
  table.labels = {"clear"};
  const std::string path = temp_path("nodes.geojson");
  vg::write_geojson(path, table, "urn:ogc:def:crs:EPSG::28992");
  const auto doc = nlohmann::json::parse(std::ifstream(path));
  CHECK(doc["type"] == "FeatureCollection");
  CHECK(doc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::28992");
  REQUIRE(doc["features"].size() == 2);
  const auto& p = doc["features"][0]["properties"];
  CHECK(p["node"] == 0);
  CHECK(p["degree"] == 1);
  CHECK(p["sum:clear"] == 0.5);
  CHECK(p["avg:clear"] == 0.5);
  CHECK(doc["features"][1]["properties"]["avg:clear"].is_null());  // degree 0: no average
  std::string crs;
  const auto back = vg::read_nodes(path, &crs);
  CHECK(crs == "urn:ogc:def:crs:EPSG::28992");
  REQUIRE(back.size() == 2);
  CHECK(back[0] == eyes[0]);  // bit for bit: shortest round-trip numbers
  CHECK(back[1] == eyes[1]);
  CHECK(vg::geojson_crs_name("https://www.opengis.net/def/crs/EPSG/0/7415") == "urn:ogc:def:crs:EPSG::7415");
  std::remove(path.c_str());
}

TEST_CASE("GeoJSON node files: MultiPoint, a bare geometry, and clear errors", "[visgraph][geojson]") {
  const std::string path = temp_path("in.geojson");
  write(path, R"({"type":"FeatureCollection","features":[
    {"type":"Feature","geometry":{"type":"MultiPoint","coordinates":[[1,2,3],[4,5,6]]},"properties":{}},
    {"type":"Feature","geometry":{"type":"Point","coordinates":[7,8,9]},"properties":null}]})");
  CHECK(vg::read_nodes(path).size() == 3);
  write(path, R"({"type":"Point","coordinates":[1,2,3]})");
  CHECK(vg::read_nodes(path).size() == 1);
  write(path, R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":"Point","coordinates":[1,2,3]}},
    {"type":"Feature","geometry":{"type":"Point","coordinates":[1,2]}}]})");
  CHECK_THAT(read_error(path), Catch::Contains(path) && Catch::Contains("feature 1") && Catch::Contains("no z"));
  write(path, R"({"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}})");
  CHECK_THAT(read_error(path), Catch::Contains(path) && Catch::Contains("Polygon"));
  write(path, "{\"type\": \"FeatureCollection\",\n \"features\": [,]}");
  CHECK_THAT(read_error(path), Catch::Contains(path) && Catch::Contains("line 2"));
  write(path, R"({"type":"FeatureCollection","features":[]})");
  CHECK_THAT(read_error(path), Catch::Contains("no points"));
  std::remove(path.c_str());
}
