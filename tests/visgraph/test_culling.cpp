// Exact culling gives the results of casting every pair, bit for bit:
// degree, the fixed-point S_S sums, distance statistics, visible and
// coincident pair counts and the edge list (same pairs, same order), on the
// five classic layouts, a small synthetic city, random scenes with grazing
// geometry (nodes on the lattice of the obstacles' corners) and a real
// CityJSON district.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/generators.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <cstdint>
#include <random>
#include <string>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

struct Run {
  vg::VisibilityResult result;
  std::vector<vg::Edge> edges;
};

Run run(const vg::Scene& scene, const std::vector<Vector3d>& nodes, bool culling, bool with_edges,
        bool eye_plane = true) {
  vg::VisibilityOptions o;
  o.sigmas = {0.0, 1.5e-4, 0.0045, 0.02874311, 0.3};
  o.distance_stats = true;
  o.culling = culling;
  o.eye_plane = eye_plane;
  o.threads = 2;
  Run r;
  if (with_edges)
    o.edge_sink = [&r](const std::vector<vg::Edge>& block) { r.edges.insert(r.edges.end(), block.begin(), block.end()); };
  r.result = vg::all_to_all(scene, nodes, o);
  return r;
}

// Culled against brute force; returns the culled run for further checks.
vg::VisibilityResult check_identical(const vg::Scene& scene, const std::vector<Vector3d>& nodes, bool with_edges) {
  const Run brute = run(scene, nodes, false, with_edges);
  const Run culled = run(scene, nodes, true, with_edges);
  const vg::VisibilityResult& b = brute.result;
  const vg::VisibilityResult& c = culled.result;
  CHECK(b.pairs_culled_visible + b.pairs_culled_blocked == 0);
  CHECK(c.degree == b.degree);
  REQUIRE(c.sum.size() == b.sum.size());
  for (std::size_t k = 0; k < b.sum.size(); ++k) CHECK(same_bits(c.sum[k], b.sum[k]));
  CHECK(same_bits(c.mean_distance, b.mean_distance));
  CHECK(same_bits(c.max_distance, b.max_distance));
  CHECK(c.pairs_visible == b.pairs_visible);
  CHECK(c.coincident_pairs == b.coincident_pairs);
  CHECK(c.pairs_cast <= b.pairs_cast);
  if (with_edges) {
    REQUIRE(culled.edges.size() == brute.edges.size());
    std::size_t differ = 0;
    for (std::size_t e = 0; e < brute.edges.size(); ++e)
      differ += culled.edges[e].i != brute.edges[e].i || culled.edges[e].j != brute.edges[e].j ||
                std::memcmp(&culled.edges[e].distance, &brute.edges[e].distance, sizeof(double)) != 0;
    CHECK(differ == 0);
  }
  return c;
}

std::vector<Vector3d> grid_nodes(const vg::Scene& scene, double spacing, std::vector<std::string> walkable) {
  vg::NodeGridOptions o;
  o.spacing = spacing;
  o.walkable = std::move(walkable);
  return vg::generate_nodes(scene, o).eyes;
}
}  // namespace

TEST_CASE("culling: the five classic layouts, identical to casting every pair", "[visgraph][culling]") {
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    const vg::Scene scene(vg::classic_layout(k));
    const auto nodes = grid_nodes(scene, 1.0, vg::classic_layout_walkable_groups());
    INFO(vg::classic_layout_name(k) << ", " << nodes.size() << " nodes");
    const vg::VisibilityResult c = check_identical(scene, nodes, k == 0);
    // The culling decides many pairs (a check that it is not trivially off;
    // how many is the benchmark's business).
    CHECK(c.pairs_culled_visible > 0);
    CHECK(c.pairs_culled_blocked > 0);
    CHECK(c.pairs_culled_visible + c.pairs_culled_blocked > c.pairs_total / 4);
  }
}

TEST_CASE("culling: a small synthetic city, identical to casting every pair", "[visgraph][culling]") {
  vg::CityOptions city;
  city.rings = 1;
  const vg::Scene scene(vg::synthetic_city(city));
  auto nodes = grid_nodes(scene, 3.0, vg::city_walkable_groups());
  INFO(nodes.size() << " nodes");
  const vg::VisibilityResult c = check_identical(scene, nodes, true);
  CHECK(c.pairs_culled_blocked > 0);
  CHECK(c.pairs_culled_visible > 0);
}

TEST_CASE("culling: random scenes with grazing sight lines, identical to casting every pair", "[visgraph][culling]") {
  std::mt19937_64 rng(31337);
  std::uniform_int_distribution<int> cell(0, 29);
  for (int trial = 0; trial < 4; ++trial) {
    // Boxes and nodes on the integer lattice: many sight lines pass exactly
    // through box edges and corners, where Embree's answer is a matter of
    // rounding; culling must leave each of them to the same ray.
    Mesh m;
    add_floor(m, 0, 30, 0, 30, 0, "floor");
    for (int b = 0; b < 10; ++b) {
      const double x = cell(rng), y = cell(rng);
      add_box(m, {x, y, 0}, {x + 1 + cell(rng) % 5, y + 1 + cell(rng) % 5, 1.0 + cell(rng) % 4}, "obstacle");
    }
    std::vector<Vector3d> nodes;
    for (int i = 0; i < 500; ++i) nodes.emplace_back(cell(rng), cell(rng), 1.0 + (i % 3));
    for (int i = 0; i < 10; ++i) nodes.push_back(nodes[static_cast<std::size_t>(i)]);  // coincident pairs
    if (trial == 3) {  // UTM-sized coordinates: the scene is recentred, the margins follow its extent
      const Vector3d offset(512345.25, 4123456.5, 312.0);
      for (Vector3d& v : m.vertices) v += offset;
      for (Vector3d& p : nodes) p += offset;
    }
    const vg::Scene scene(m);
    INFO("trial " << trial);
    const vg::VisibilityResult c = check_identical(scene, nodes, trial == 0);
    CHECK(c.pairs_culled_visible + c.pairs_culled_blocked > 0);
  }
}

TEST_CASE("culling: the Delfshaven CityJSON (real data, shared/), identical to casting every pair", "[visgraph][culling]") {
  // ../shared/data/cityjson/README.md: 853 LoD2 buildings (walls triangulated
  // from polygons, no terrain: a ground plane is added as `vg` does).
  const std::string path =
      std::string(ATTENUVIS_TEST_DATA_DIR) + "/../../../shared/data/cityjson/rotterdam-delfshaven-3-20.city.json";
  if (!std::filesystem::exists(path)) {
    WARN("skipped: " << path << " is absent");
    return;
  }
  vg::Mesh m = vg::load_cityjson(path, {});
  vg::add_ground_plane(m);
  const vg::Scene scene(m);
  const auto nodes = grid_nodes(scene, 16.0, {});
  INFO(nodes.size() << " nodes");
  const vg::VisibilityResult c = check_identical(scene, nodes, true);
  CHECK(c.pairs_culled_blocked > 0);
}

namespace {
// A wall quad a, b, c, d whose two triangles share the diagonal's vertices
// (indices), as model walls do: one planar occluder.
void add_wall(Mesh& m, const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  const auto g = static_cast<std::uint32_t>(m.add_group("wall"));
  const auto v = static_cast<std::uint32_t>(m.vertices.size());
  for (const Vector3d& p : {a, b, c, d}) m.vertices.push_back(p);
  m.triangles.push_back({v, v + 1, v + 2});
  m.triangles.push_back({v, v + 2, v + 3});
  m.triangle_group.push_back(g);
  m.triangle_group.push_back(g);
}
}  // namespace

TEST_CASE("culling in the eyes' plane: walls ending just below or above the eyes, hanging and leaning walls",
          "[visgraph][culling]") {
  // Eyes at one height h (to within 1e-7 m, well inside the plane's
  // tolerance of a hundredth of the margin), on the integer lattice; walls
  // with lattice ends, so sight lines graze their ends.  Each wall is one
  // of: full height; its top 0.2 mm below h (the sight lines pass over it:
  // a wall taken as reaching the eyes' plane, e.g. by its footprint, would
  // block them); its top 0.2 mm above h (it blocks, but within the margin:
  // left to rays); hanging from 0.2 mm above h (the lines pass under it);
  // leaning 45 or 0.06 degrees off vertical (its trace at h is not its
  // foot).  Some eyes stand within the margin of a wall's plane, and a
  // few above every wall, off the plane.  A fan that took any of them
  // wrongly changes some pair's answer.
  const double h = 1.5;
  std::mt19937_64 rng(4242);
  std::uniform_int_distribution<int> at(1, 39), length(1, 8), kind(0, 5), dir(0, 2);
  for (int trial = 0; trial < 3; ++trial) {
    Mesh m;
    add_floor(m, 0, 40, 0, 40, 0, "floor");
    for (int w = 0; w < 30; ++w) {
      const double x = at(rng), y = at(rng), l = length(rng);
      const int d = dir(rng);
      const Vector3d a(x, y, 0);
      const Vector3d b = d == 0 ? Vector3d(x + l, y, 0) : d == 1 ? Vector3d(x, y + l, 0) : Vector3d(x + l, y + l, 0);
      // The wall's normal direction in the plane, for leaning walls.
      const Vector3d across =
          d == 0 ? Vector3d(0, 1, 0) : d == 1 ? Vector3d(-1, 0, 0) : Vector3d(-1, 1, 0).normalized();
      double bottom = 0, top = 4, lean = 0;
      switch (kind(rng)) {
        case 1: top = h - 2e-4; break;
        case 2: top = h + 2e-4; break;
        case 3: bottom = h + 2e-4; break;
        case 4: lean = 1.0; break;     // 45 degrees
        case 5: lean = 1e-3; break;    // nearly vertical
        default: break;
      }
      const Vector3d up0(0, 0, bottom), up1 = Vector3d(0, 0, top) + lean * top * across;
      add_wall(m, a + up0 + lean * bottom * across, b + up0 + lean * bottom * across, b + up1, a + up1);
    }
    std::vector<Vector3d> nodes;
    for (int j = 0; j <= 40; j += 2)
      for (int i = 0; i <= 40; i += 2) {
        nodes.emplace_back(i, j, h + 1e-7 * ((i + j) % 3));
        // Eyes half a millimetre off the walls' lines, within the margin
        // (1.4 mm here) of their planes.
        if ((i + j) % 6 == 0) nodes.emplace_back(i + 5e-4, j + 1.0, h);
        if ((i + j) % 6 == 2) nodes.emplace_back(i + 1.0, j - 5e-4, h);
        // A few eyes above every wall (on a roof): off the plane, they see
        // over the walls that block the others.
        if (i % 8 == 0 && j % 8 == 4) nodes.emplace_back(i + 0.5, j, 5.0);
      }
    const vg::Scene scene(m);
    INFO("trial " << trial << ", " << nodes.size() << " nodes");
    const vg::VisibilityResult c = check_identical(scene, nodes, trial == 0);
    // The plane decides pairs here: fewer are cast with it than without.
    const Run without = run(scene, nodes, true, false, false);
    CHECK(c.pairs_cast < without.result.pairs_cast);
    CHECK(c.degree == without.result.degree);
  }
}
