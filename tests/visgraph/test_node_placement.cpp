// Where generated nodes stand (nodes.hpp): the data's classes by default,
// never a roof; the lowest-surface rule for scenes without classes; the
// ground plane for models without ground; counts per class and the elevated
// nodes.  Expected counts follow from the geometry on a 1 m grid of cell
// centres, as worked out beside each check.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
std::map<std::string, std::size_t> counts(const vg::NodeSet& n) {
  std::map<std::string, std::size_t> out;
  for (const auto& s : n.by_surface) out[s.name] = s.nodes;
  return out;
}
}  // namespace

TEST_CASE("CityJSON default: nodes on terrain and road, none on the roof", "[visgraph][nodes]") {
  // box_on_terrain_v1.0: 30 x 30 m TINRelief, 10 x 10 x 6 m building at
  // [10,20]^2, Road y in [-4,-1].  Grid 30 x 34 cells: 3 rows x 30 road
  // cells, 1 row over nothing (y in [-1, 0]), 900 terrain cells less the 100
  // under the roof.
  const std::string path = std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/cityjson/box_on_terrain_v1.0.city.json";
  const vg::Scene scene(vg::load_cityjson(path));
  vg::NodeGridOptions o;
  const vg::NodeSet n = vg::generate_nodes(scene, o);
  CHECK(n.cells == 1020);
  CHECK(n.eyes.size() == 890);
  CHECK(counts(n) == std::map<std::string, std::size_t>{{"TINRelief", 800}, {"Road", 90}});
  CHECK(n.covered == 100);
  CHECK(n.no_surface == 30);
  CHECK(n.elevated == 0);
  for (const auto& e : n.eyes) CHECK(e.z() == Approx(1.7).margin(1e-6));
  // Asked for explicitly, the roof carries the nodes: 100 of them, 6 m above
  // the terrain under them, so all elevated.
  o.walkable = {"RoofSurface"};
  const vg::NodeSet roof = vg::generate_nodes(scene, o);
  CHECK(roof.eyes.size() == 100);
  CHECK(roof.elevated == 100);
  CHECK(roof.max_elevation == Approx(6.0).margin(1e-4));
  // A group (the city object id) selects too; an unknown name names the
  // scene's groups and classes.
  o.walkable = {"road-1"};
  CHECK(vg::generate_nodes(scene, o).eyes.size() == 90);
  o.walkable = {"Pavement"};
  CHECK_THROWS_WITH(vg::generate_nodes(scene, o),
                    Catch::Contains("Pavement") && Catch::Contains("3 groups") && Catch::Contains("TINRelief"));
}

TEST_CASE("without classes: the lowest surface outside closed solids", "[visgraph][nodes]") {
  // 10 x 10 m terrain at z = 0, a pavement at z = 0.2 over x in [0, 4], and a
  // closed 3 x 2 x 3 m box on the terrain at [6,9] x [2,4]: 100 cells, 6
  // inside the box (covered), 40 on the pavement (eye at 1.9 m), 54 on the
  // terrain (eye 1.7 m).
  Mesh m;
  add_floor(m, 0, 10, 0, 10, 0, "terrain");
  add_floor(m, 0, 4, 0, 10, 0.2, "pavement");
  add_box(m, {6, 2, 0}, {9, 4, 3}, "house");
  const vg::Scene scene(m);
  const vg::NodeSet n = vg::generate_nodes(scene, vg::NodeGridOptions{});
  CHECK(n.eyes.size() == 94);
  CHECK(n.covered == 6);
  CHECK(counts(n) == std::map<std::string, std::size_t>{{"pavement", 40}, {"terrain", 54}});
  std::size_t high = 0;
  for (const auto& e : n.eyes) high += std::abs(e.z() - 1.9) < 1e-6;
  CHECK(high == 40);
}

TEST_CASE("a model without ground finds nothing until a ground plane is added", "[visgraph][nodes]") {
  // Two closed boxes standing at z = 2 on nothing; their xy bounding box
  // [0,12] x [0,5] grown by 1 m gives the plane 14 x 7 m: 98 cells, of which
  // the 2 x (4 x 5) = 40 under the boxes are covered.
  Mesh m;
  add_box(m, {0, 0, 2}, {4, 5, 8}, "building-a");
  add_box(m, {8, 0, 2}, {12, 5, 6}, "building-b");
  {
    const vg::Scene scene(m);
    const vg::NodeSet n = vg::generate_nodes(scene, vg::NodeGridOptions{});
    CHECK(n.eyes.empty());
    CHECK(n.no_surface > 0);
  }
  vg::add_ground_plane(m);
  const vg::Scene scene(m);
  const vg::NodeSet n = vg::generate_nodes(scene, vg::NodeGridOptions{});
  CHECK(n.cells == 98);
  CHECK(n.eyes.size() == 58);
  CHECK(n.covered == 40);
  CHECK(counts(n) == std::map<std::string, std::size_t>{{vg::kGroundPlaneGroup, 58}});
  for (const auto& e : n.eyes) CHECK(e.z() == Approx(2 + 1.7).margin(1e-6));
}
