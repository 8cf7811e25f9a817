// Node generation: grid of cell centres on walkable surfaces, found by rays
// cast down; covered, steep cells dropped; node files.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

TEST_CASE("a flat floor gives one node per cell centre at eye height", "[visgraph][nodes]") {
  Mesh m;
  add_floor(m, 100, 110, 200, 205, 3.0, "floor");
  const vg::Scene scene(m);
  vg::NodeGridOptions o;
  const vg::NodeSet n = vg::generate_nodes(scene, o);
  REQUIRE(n.eyes.size() == 50);
  CHECK(n.cells == 50);
  CHECK(n.eyes.front().isApprox(Vector3d(100.5, 200.5, 4.7), 1e-12));
  CHECK(n.eyes.back().isApprox(Vector3d(109.5, 204.5, 4.7), 1e-12));
  o.spacing = 0.5;
  o.eye_height = 1.0;
  const vg::NodeSet half = vg::generate_nodes(scene, o);
  CHECK(half.eyes.size() == 200);
  CHECK(half.eyes.front().z() == Approx(4.0));
}

TEST_CASE("obstacle tops are covered cells unless they are walkable", "[visgraph][nodes]") {
  Mesh m;
  add_floor(m, 0, 10, 0, 10, 0, "floor");
  add_box(m, {2, 2, 0}, {5, 4, 3}, "obstacle");  // covers 3 x 2 cells
  const vg::Scene scene(m);
  vg::NodeGridOptions o;
  o.walkable = {"floor"};
  const vg::NodeSet n = vg::generate_nodes(scene, o);
  CHECK(n.eyes.size() == 94);
  CHECK(n.covered == 6);
  o.walkable = {"*"};  // every surface walkable: roof nodes at 3 + 1.7 m
  const vg::NodeSet all = vg::generate_nodes(scene, o);
  CHECK(all.eyes.size() == 100);
  std::size_t on_roof = 0;
  for (const auto& p : all.eyes) on_roof += std::abs(p.z() - 4.7) < 1e-9;
  CHECK(on_roof == 6);
  o.walkable = {"pavement"};
  CHECK_THROWS_WITH(vg::generate_nodes(scene, o), Catch::Contains("pavement"));
}

TEST_CASE("surfaces steeper than the maximum slope are dropped", "[visgraph][nodes]") {
  // A ramp rising 30 degrees along x.
  Mesh m;
  const double rise = 10 * std::tan(30.0 * 3.14159265358979323846 / 180);
  add_quad(m, {0, 0, 0}, {10, 0, rise}, {10, 4, rise}, {0, 4, 0}, "ramp");
  const vg::Scene scene(m);
  vg::NodeGridOptions o;
  o.max_slope_deg = 20;
  const vg::NodeSet steep = vg::generate_nodes(scene, o);
  CHECK(steep.eyes.empty());
  CHECK(steep.too_steep == 40);
  o.max_slope_deg = 35;
  const vg::NodeSet ok = vg::generate_nodes(scene, o);
  REQUIRE(ok.eyes.size() == 40);
  // The node sits eye height above the ramp under the cell centre.
  CHECK(ok.eyes.front().z() == Approx(0.5 * rise / 10 + 1.7).epsilon(1e-6));
}

TEST_CASE("classic layouts give the published node counts", "[visgraph][nodes]") {
  // The seed paper's test layouts: 1 m grid of cell centres on the floor of
  // the five 50 x 50 m layouts (counts from the footprints, layouts.cpp).
  const std::size_t expected[5] = {2424, 2000, 2400, 2000, 2460};
  for (int layout = 0; layout < 5; ++layout) {
    const vg::Scene scene(vg::classic_layout(layout));
    vg::NodeGridOptions o;
    o.walkable = {"floor"};
    const vg::NodeSet n = vg::generate_nodes(scene, o);
    INFO("layout " << layout);
    CHECK(n.eyes.size() == expected[layout]);
    CHECK(n.covered == 2500 - expected[layout]);
  }
}

TEST_CASE("node files: x,y,z rows, header allowed, errors name file and line", "[visgraph][nodes]") {
  const std::string path = "test_nodes_input.csv";
  {
    std::ofstream f(path);
    f << "x,y,z\n1,2,3\n# comment\n4.5, 5.5 ,6.5\n";
  }
  const auto nodes = vg::read_nodes_csv(path);
  REQUIRE(nodes.size() == 2);
  CHECK(nodes[1].isApprox(Vector3d(4.5, 5.5, 6.5)));
  {
    std::ofstream f(path);
    f << "1,2,3\n4,nan,6\n";
  }
  CHECK_THROWS_WITH(vg::read_nodes_csv(path), Catch::Contains(path + ":2"));
  {
    std::ofstream f(path);
    f << "1,2,3\n4,five,6\n";
  }
  CHECK_THROWS_WITH(vg::read_nodes_csv(path), Catch::Contains(path + ":2"));
  std::remove(path.c_str());
  CHECK_THROWS_WITH(vg::read_nodes_csv("no/such/nodes.csv"), Catch::Contains("no/such/nodes.csv"));
  CHECK(vg::parse_point("1,2.5,-3").isApprox(Vector3d(1, 2.5, -3)));
  CHECK_THROWS(vg::parse_point("1,2"));
  CHECK_THROWS(vg::parse_point("1,inf,2"));
}
