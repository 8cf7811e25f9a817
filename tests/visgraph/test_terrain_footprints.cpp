// Terrain surfaces from height grids (terrain.hpp) and buildings extruded
// from footprints (footprints.hpp): the surface Embree meets is the one
// height_at describes, cells without data are named, and every prism is a
// closed outward-facing solid of the footprint's area times its height (the
// divergence theorem, summed over its triangles), holes and multipolygons
// included.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/footprints.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/terrain.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {

// A 4 x 3 grid of 2 m cells, north-up (dy < 0), heights from a function.
vg::HeightGrid grid(double (*height)(double, double)) {
  vg::HeightGrid g;
  g.x0 = 101;
  g.y0 = 205;
  g.dx = 2;
  g.dy = -2;
  g.cols = 4;
  g.rows = 3;
  g.col0 = 10;
  g.row0 = 20;
  for (std::size_t r = 0; r < g.rows; ++r)
    for (std::size_t c = 0; c < g.cols; ++c) {
      const Eigen::Vector2d p = g.centre(c, r);
      g.z.push_back(height(p.x(), p.y()));
    }
  return g;
}

double bumpy(double x, double y) { return std::sin(x) + std::cos(0.5 * y) + 0.1 * x * y / 100; }

// The volume a closed, outward-facing triangle mesh encloses: the sum of the
// signed volumes of the tetrahedra from the origin to each triangle.
double enclosed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

vg::BuildingFootprint square_footprint(const std::string& id, double x0, double y0, double side, double height) {
  vg::BuildingFootprint f;
  f.id = id;
  f.height = height;
  f.polygons.push_back({{{{x0, y0, 0}, {x0 + side, y0, 0}, {x0 + side, y0 + side, 0}, {x0, y0 + side, 0}}}});
  return f;
}

}  // namespace

TEST_CASE("the terrain Embree meets is the surface height_at describes", "[visgraph][terrain]") {
  const vg::HeightGrid g = grid(bumpy);
  Mesh m;
  CHECK(vg::add_terrain(m, g) == 2 * 3 * 2);
  const vg::Scene scene(m);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> ux(101, 107), uy(201, 205);
  for (int k = 0; k < 500; ++k) {
    const double x = ux(rng), y = uy(rng);
    const vg::Scene::Hit hit =
        scene.intersect(scene.to_local({x, y, 100}), Eigen::Vector3d(0, 0, -1), 0, 200);
    REQUIRE(hit.found);
    CHECK(hit.normal.z() > 0);  // facing up
    CHECK(100 - hit.t == Approx(g.height_at(x, y)).margin(1e-5));
  }
  // At the cell centres, the cells' own heights; outside them, none.
  CHECK(g.height_at(103, 203) == g.at(1, 1));
  CHECK(std::isnan(g.height_at(100.9, 203)));
  CHECK_FALSE(g.covers(108, 203));
}

TEST_CASE("cells without data leave holes, named where nodes would need them", "[visgraph][terrain]") {
  vg::HeightGrid g = grid([](double, double) { return 5.0; });
  g.z[1 * g.cols + 2] = std::nan("");  // window cell (2, 1): raster cell (12, 21) at x = 105, y = 203
  Mesh m;
  CHECK(vg::add_terrain(m, g) == 2 * (6 - 4));  // the four blocks around the cell are left out
  CHECK(std::isnan(g.height_at(104.5, 203.5)));
  CHECK(g.missing_cell(104.5, 203.5) == "cell (column 12, row 21) at x = 105, y = 203");
  CHECK(g.missing_cell(101.5, 204.5) == "");
  CHECK_THROWS_WITH(vg::check_nodes_on_terrain(g, {{101.5, 204.5, 6.7}, {105.5, 202, 6.7}}, "dem.tif"),
                    "dem.tif has no data at cell (column 12, row 21) at x = 105, y = 203, under node 2 (x = 105.5, y = 202)");
  CHECK_THROWS_WITH(vg::check_nodes_on_terrain(g, {{99, 202, 6.7}}, "dem.tif"),
                    Catch::Contains("node 1 (x = 99, y = 202) lies outside the terrain read from dem.tif"));
  // Under a building the hole is harmless; in the open it is named.
  Mesh house;
  add_box(house, {104.5, 202.5, 5}, {105.5, 203.5, 9}, "house");
  CHECK(vg::exposed_missing_cell(g, vg::Scene(house)) == "");
  Mesh shed;
  add_box(shed, {101, 201, 5}, {102, 202, 7}, "shed");
  CHECK(vg::exposed_missing_cell(g, vg::Scene(shed)) == "cell (column 12, row 21) at x = 105, y = 203");
}

TEST_CASE("footprints become closed prisms facing out, holes and parts included", "[visgraph][footprints]") {
  // A 30 m square around a 10 m courtyard, 9 m tall: 800 m^2 x 9 m.
  vg::BuildingFootprint court = square_footprint("court", 0, 0, 30, 9);
  court.polygons[0].rings.push_back({{10, 10, 0}, {10, 20, 0}, {20, 20, 0}, {20, 10, 0}, {10, 10, 0}});
  // Two 8 m squares, 6 m tall, given clockwise: 2 x 64 m^2 x 6 m.
  vg::BuildingFootprint pair;
  pair.id = "pair";
  pair.height = 6;
  pair.polygons.push_back({{{{40, 0, 0}, {40, 8, 0}, {48, 8, 0}, {48, 0, 0}}}});
  pair.polygons.push_back({{{{50, 0, 0}, {50, 8, 0}, {58, 8, 0}, {58, 0, 0}}}});
  vg::FootprintGround ground;
  ground.plane_z = 2;
  const Mesh m = vg::extrude_footprints({court, pair}, ground, "test");
  CHECK(enclosed_volume(m) == Approx(800 * 9 + 2 * 64 * 6).epsilon(1e-12));
  CHECK(m.groups == std::vector<std::string>{"court", "pair"});
  const vg::MeshStats stats = vg::mesh_stats(m);
  CHECK(stats.lower.z() == 2);
  CHECK(stats.upper.z() == 11);
  for (const auto& c : stats.classes) {
    if (c.name == "RoofSurface" || c.name == "GroundSurface") CHECK(c.projected_area == Approx(800 + 128));
    if (c.name == "WallSurface") CHECK(c.projected_area == Approx(0).margin(1e-9));
  }
  // Each building alone encloses its own volume: its walls face out of it.
  CHECK(enclosed_volume(vg::extrude_footprints({court}, ground, "test")) == Approx(800 * 9));
}

TEST_CASE("footprints stand on the lowest terrain or vertex height under them", "[visgraph][footprints]") {
  const vg::HeightGrid g = grid([](double x, double y) { return 0.5 * x + 0.25 * y; });
  vg::FootprintGround on_terrain;
  on_terrain.terrain = &g;
  const Mesh m = vg::extrude_footprints({square_footprint("a", 102, 202, 2, 10)}, on_terrain, "test");
  const double lowest = 0.5 * 102 + 0.25 * 202;  // the corner (102, 202)
  CHECK(vg::mesh_stats(m).lower.z() == Approx(lowest));
  CHECK(vg::mesh_stats(m).upper.z() == Approx(lowest + 10));
  vg::BuildingFootprint sloped = square_footprint("b", 0, 0, 10, 5);
  for (auto& p : sloped.polygons[0].rings[0]) p.z() = 0.2 * p.x();  // 2 m of rise across it
  vg::FootprintGround own_z;
  own_z.vertex_z = true;
  const Mesh s = vg::extrude_footprints({sloped}, own_z, "test");
  CHECK(vg::mesh_stats(s).upper.z() == 5);
  CHECK(enclosed_volume(s) == Approx(100 * 5 - 100 * 1).epsilon(1e-12));  // the floor rises 1 m on average
  sloped.height = 1.5;
  CHECK_THROWS_WITH(vg::extrude_footprints({sloped}, own_z, "test"),
                    Catch::Contains("feature b: height 1.5 m is less than the 2 m its base rises"));
}

TEST_CASE("footprints that are not simple polygons are refused by feature", "[visgraph][footprints]") {
  const vg::FootprintGround ground;
  vg::BuildingFootprint bow = square_footprint("7", 0, 0, 10, 5);
  bow.polygons[0].rings[0] = {{0, 0, 0}, {10, 10, 0}, {10, 0, 0}, {0, 10, 0}};
  CHECK_THROWS_WITH(vg::extrude_footprints({bow}, ground, "fp.gpkg"),
                    Catch::Contains("fp.gpkg: feature 7, outline intersects itself"));
  vg::BuildingFootprint line = square_footprint("8", 0, 0, 10, 5);
  line.polygons[0].rings[0] = {{0, 0, 0}, {10, 0, 0}, {0, 0, 0}};
  CHECK_THROWS_WITH(vg::extrude_footprints({line}, ground, "fp.gpkg"),
                    Catch::Contains("feature 8, outline has 2 distinct vertices: a ring needs at least three"));
  vg::BuildingFootprint astray = square_footprint("9", 0, 0, 10, 5);
  astray.polygons[0].rings.push_back({{20, 20, 0}, {20, 22, 0}, {22, 22, 0}});
  CHECK_THROWS_WITH(vg::extrude_footprints({astray}, ground, "fp.gpkg"),
                    Catch::Contains("feature 9") && Catch::Contains("cannot be triangulated"));
  vg::BuildingFootprint flat = square_footprint("10", 0, 0, 10, 0);
  CHECK_THROWS_WITH(vg::extrude_footprints({flat}, ground, "fp.gpkg"),
                    Catch::Contains("feature 10: height 0 is not a positive number"));
}
