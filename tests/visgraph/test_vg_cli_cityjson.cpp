// `attenuvis vg` and `attenuvis scene info` on CityJSON: nodes where the data
// say people walk (never on roofs), the ground plane for a model without
// terrain, the GeoJSON layer in the scene's CRS, the heatmap, a small summary,
// group lists cut short in messages.  Small files of tests/data/visgraph/
// cityjson/, and the real Delfshaven model ([slow], when shared/ holds it).
#include "cli_test_support.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

using namespace clitest;
using Catch::Matchers::Contains;

namespace {
std::string cityjson(const std::string& name) {
  return std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/cityjson/" + name;
}

// Every node of the GeoJSON layer, with the checks a GIS reader makes.
nlohmann::json read_layer(const std::string& path, const std::string& crs, const std::vector<std::string>& properties) {
  std::ifstream in(path);
  REQUIRE(in);
  const nlohmann::json doc = nlohmann::json::parse(in);
  CHECK(doc["type"] == "FeatureCollection");
  CHECK(doc["crs"]["properties"]["name"] == crs);
  REQUIRE(!doc["features"].empty());
  for (const std::string& p : properties) CHECK(doc["features"][0]["properties"].contains(p));
  CHECK(doc["features"][0]["geometry"]["coordinates"].size() == 3);
  return doc;
}
}  // namespace

TEST_CASE("vg on CityJSON: nodes on terrain and road, GeoJSON in the scene's CRS", "[visgraph][cli]") {
  // box_on_terrain_v1.0: 800 terrain and 90 road cells, 100 under the roof
  // (test_node_placement.cpp).
  TempDir dir;
  const Run r = run("vg " + cityjson("box_on_terrain_v1.0.city.json") + " --conditions clear,fog:advection --out " +
                    (dir / "n.csv") + " --geojson " + (dir / "n.geojson") + " --heatmap " + (dir / "n.png") +
                    " --summary " + (dir / "s.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("TINRelief 800") && Contains("Road 90"));
  const Csv csv = read_csv(dir / "n.csv");
  CHECK(csv.rows.size() == 890);
  const auto layer = read_layer(dir / "n.geojson", "urn:ogc:def:crs:EPSG::28992",
                                {"node", "degree", "sum:clear", "avg:clear", "sum:fog:advection", "avg:fog:advection"});
  CHECK(layer["features"].size() == 890);
  CHECK(std::filesystem::file_size(dir / "n.png") > 1000);
  std::ifstream summary(dir / "s.json");
  const auto s = nlohmann::json::parse(summary);
  CHECK(s["scene"]["format"] == "CityJSON 1.0");
  CHECK(s["node_grid"]["nodes_by_surface"]["TINRelief"] == 800);
  CHECK(s["node_grid"]["elevated_nodes"] == 0);
  // A small scene keeps the default 1 m: nothing to coarsen, no rule recorded.
  CHECK(s["node_grid"]["spacing_m"] == 1.0);
  CHECK(!s["node_grid"].contains("spacing_rule"));
}

TEST_CASE("vg on a building without terrain offers and adds a ground plane", "[visgraph][cli]") {
  // solid_lods_hole_v1.1: one L-shaped house, 64 m^2, over [0,10]^2 and
  // nothing else.  The plane spans the bounding box grown by 1 m: 12 x 12
  // cells, 64 under the roof: 80 nodes.
  TempDir dir;
  const std::string house = cityjson("solid_lods_hole_v1.1.city.json");
  Run r = run("vg " + house + " --conditions clear --ground-plane no --out " + (dir / "a.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("no ground") && Contains("--ground-plane yes"));
  CHECK_FALSE(std::filesystem::exists(dir / "a.csv"));
  r = run("vg " + house + " --conditions clear --out " + (dir / "b.csv"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("warning") && Contains("ground plane") && Contains("GroundPlane 80"));
  // Asked for, the roof carries the nodes, 8 m above the ground: a warning.
  r = run("vg " + house + " --conditions clear --walkable RoofSurface --out " + (dir / "c.csv"));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("64 nodes stand more than 2 m above"));
  r = run("vg " + house + " --conditions clear --walkable Pavement --out " + (dir / "d.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("Pavement") && Contains("1 groups") && Contains("RoofSurface"));
}

TEST_CASE("scene info lists groups once, sorted, with classes", "[visgraph][cli]") {
  Run r = run("scene info " + cityjson("box_on_terrain_v1.0.city.json") + " --groups");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("format: CityJSON 1.0") && Contains("crs: urn:ogc:def:crs:EPSG::28992") &&
                           Contains("RoofSurface, WallSurface") && Contains("sorted by name"));
  const auto b = r.output.find("  building-1"), rd = r.output.find("  road-1"), t = r.output.find("  terrain");
  CHECK((b < rd && rd < t));
  r = run("scene info " + cityjson("bad_vertex_index.city.json"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("bad_vertex_index.city.json") && Contains("out of range"));
}

TEST_CASE("vg on the Delfshaven CityJSON: no node on a roof, every output written", "[visgraph][cli][slow]") {
  // ../shared/data/cityjson/README.md: 853 LoD2 buildings, no terrain.  The
  // default options stand the nodes on a ground plane at the lowest z, and,
  // since 1 m gives 549,080 nodes (1.5e11 pairs, far above the default 2e9),
  // coarsen the grid to the first spacing that fits: 3 m, 60,898 nodes.
  const std::string model = std::string(ATTENUVIS_TEST_DATA_DIR) +
                            "/../../../shared/data/cityjson/rotterdam-delfshaven-3-20.city.json";
  if (!std::filesystem::exists(model)) {
    WARN("skipped: " << model << " is absent");
    return;
  }
  TempDir dir;
  const Run r = run("vg " + model + " --conditions clear,fog:advection --out " + (dir / "n.csv") +
                    " --geojson " + (dir / "n.geojson") + " --heatmap " + (dir / "n.png") + " --summary " +
                    (dir / "s.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("no ground") && Contains("ground plane"));
  // Group lists are cut short: no line of the report runs long (853 groups
  // spelled out would take ~35,000 characters).
  std::size_t longest = 0, start = 0;
  for (std::size_t i = 0; i <= r.output.size(); ++i)
    if (i == r.output.size() || r.output[i] == '\n' || r.output[i] == '\r') {
      longest = std::max(longest, i - start);
      start = i + 1;
    }
  CHECK(longest < 600);
  std::ifstream summary(dir / "s.json");
  const auto s = nlohmann::json::parse(summary);
  CHECK(std::filesystem::file_size(dir / "s.json") < 8000);
  const auto& by = s["node_grid"]["nodes_by_surface"];
  // On the plane, and where a cell falls on a building's GroundSurface (its
  // footprint at ground level: 1 node at 3 m), there; never on a roof.
  CHECK(!by.contains("RoofSurface"));
  CHECK(by.contains("GroundPlane"));
  for (const auto& [name, count] : by.items()) CHECK((name == "GroundPlane" || name == "GroundSurface"));
  CHECK(s["node_grid"]["elevated_nodes"] == 0);
  CHECK(s["node_grid"]["spacing_m"] == 3.0);
  CHECK_THAT(s["node_grid"]["spacing_rule"].get<std::string>(), Contains("no --spacing") && Contains("549080 nodes"));
  CHECK_THAT(r.output, Contains("spacing: no --spacing: 3 m"));
  const auto layer = read_layer(dir / "n.geojson", "urn:ogc:def:crs:EPSG::28992", {"node", "degree", "sum:clear"});
  CHECK(layer["features"].size() == s["nodes"]);
  CHECK(std::filesystem::file_size(dir / "n.png") > 1000);
}
