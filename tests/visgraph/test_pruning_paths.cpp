// all_to_all with a finite radius finds each row's partners in the x-sorted
// slab (visgraph/src/visibility.cpp), with or without an edge list; the
// results with and without edge output agree bit for bit, and the pruned
// graph is checked against the exact pass, pair by pair, through the edge
// list.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <utility>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
// Boxes on a 60 x 60 m floor and eye points among them; a few duplicated
// nodes exercise coincident pairs, equal x coordinates the sort's ties.
Mesh scene_with_nodes(std::mt19937_64& rng, std::vector<Vector3d>& nodes) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Mesh m;
  add_floor(m, 0, 60, 0, 60, 0, "floor");
  for (int b = 0; b < 12; ++b) {
    const double x = 60 * u(rng), y = 60 * u(rng);
    add_box(m, {x, y, 0}, {x + 1 + 6 * u(rng), y + 1 + 6 * u(rng), 1 + 5 * u(rng)}, "obstacle");
  }
  nodes.clear();
  for (int i = 0; i < 700; ++i) nodes.emplace_back(60 * u(rng), 60 * u(rng), 0.5 + 3 * u(rng));
  for (int i = 0; i < 20; ++i) nodes.push_back(nodes[static_cast<std::size_t>(i) * 7]);                 // coincident
  for (int i = 0; i < 20; ++i) nodes.emplace_back(nodes[static_cast<std::size_t>(i)].x(), 60 * u(rng), 1.7);  // same x
  return m;
}
}  // namespace

TEST_CASE("pruning: runs with and without edge output give identical results", "[visgraph][visibility][pruning]") {
  std::mt19937_64 rng(2024);
  std::vector<Vector3d> nodes;
  const Mesh m = scene_with_nodes(rng, nodes);
  const vg::Scene scene(m);
  for (double eps : {1e-1, 1e-3}) {
    vg::VisibilityOptions o;
    o.sigmas = {0.15, 0.4};
    o.prune_below = eps;
    o.always_prune = true;  // R = ln(1/eps)/0.15: 15.4 m and 46 m, inside the 60 m floor
    o.threads = 2;
    const vg::VisibilityResult slab = vg::all_to_all(scene, nodes, o);
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    o.edge_sink = [&](const std::vector<vg::Edge>& block) {
      for (const vg::Edge& e : block) edges.insert({e.i, e.j});
    };
    const vg::VisibilityResult tree = vg::all_to_all(scene, nodes, o);
    INFO("eps " << eps);
    CHECK(slab.pruned == tree.pruned);
    CHECK(slab.sum == tree.sum);  // bit for bit: the same integer contributions
    CHECK(slab.pairs_cast == tree.pairs_cast);
    CHECK(slab.pairs_visible == tree.pairs_visible);
    CHECK(slab.coincident_pairs == tree.coincident_pairs);
    CHECK(edges.size() == tree.pairs_visible);

    // Against the exact pass: the pruned run sees exactly the exact run's
    // visible pairs that lie within the radius.
    vg::VisibilityOptions x;
    std::size_t within = 0, missing = 0;
    x.edge_sink = [&](const std::vector<vg::Edge>& block) {
      for (const vg::Edge& e : block) {
        if (e.distance > slab.pruning_radius) continue;
        ++within;
        missing += edges.count({e.i, e.j}) == 0;
      }
    };
    vg::all_to_all(scene, nodes, x);
    CHECK(within == edges.size());
    CHECK(missing == 0);
  }
}

TEST_CASE("max distance: runs with and without edge output give the same exact degrees", "[visgraph][visibility][pruning]") {
  std::mt19937_64 rng(77);
  std::vector<Vector3d> nodes;
  const Mesh m = scene_with_nodes(rng, nodes);
  const vg::Scene scene(m);
  vg::VisibilityOptions o;
  o.sigmas = {0.01};
  o.max_distance = 12.5;
  o.distance_stats = true;
  const vg::VisibilityResult slab = vg::all_to_all(scene, nodes, o);
  o.edge_sink = [](const std::vector<vg::Edge>&) {};
  const vg::VisibilityResult tree = vg::all_to_all(scene, nodes, o);
  REQUIRE(slab.degree_exact);
  CHECK(slab.degree == tree.degree);
  CHECK(slab.sum == tree.sum);
  // Bit-identical, NaN (degree 0: nodes inside a box) included.
  REQUIRE(slab.max_distance.size() == tree.max_distance.size());
  CHECK(std::memcmp(slab.max_distance.data(), tree.max_distance.data(), slab.max_distance.size() * sizeof(double)) == 0);
  std::size_t over = 0;
  for (double d : slab.max_distance) over += !std::isnan(d) && d > 12.5;
  CHECK(over == 0);
}

TEST_CASE("pruning: a radius that covers the scene prunes nothing and keeps every column", "[visgraph][visibility][pruning]") {
  std::mt19937_64 rng(5150);
  std::vector<Vector3d> nodes;
  const Mesh m = scene_with_nodes(rng, nodes);
  const vg::Scene scene(m);
  vg::VisibilityOptions exact;
  exact.sigmas = {1.5e-4, 0.0374};  // clear air: R = ln(1e9)/1.5e-4 = 138 km
  exact.distance_stats = true;
  const vg::VisibilityResult reference = vg::all_to_all(scene, nodes, exact);
  for (bool always : {false, true}) {
    vg::VisibilityOptions o = exact;
    o.prune_below = 1e-9;
    o.always_prune = always;
    const vg::VisibilityResult r = vg::all_to_all(scene, nodes, o);
    INFO("always_prune " << always);
    // Declined (the exact pass runs) or run with nothing to drop: either way
    // every column is exact and identical to the exact pass.
    CHECK(r.degree_exact);
    CHECK(r.degree == reference.degree);
    CHECK(r.sum == reference.sum);
    REQUIRE(r.mean_distance.size() == reference.mean_distance.size());
    CHECK(std::memcmp(r.mean_distance.data(), reference.mean_distance.data(),
                      r.mean_distance.size() * sizeof(double)) == 0);
    CHECK(r.pruning_note.find("nothing pruned") != std::string::npos);
  }
  // A radius inside the scene still prunes, and says what it dropped.
  vg::VisibilityOptions o = exact;
  o.sigmas = {2.0};
  o.prune_below = 1e-1;  // R = 1.15 m on a 60 m floor: ~4% of the pairs within R along x
  const vg::VisibilityResult pruned = vg::all_to_all(scene, nodes, o);
  CHECK_FALSE(pruned.degree_exact);
  CHECK(pruned.pruning_note.find("pruned ") == 0);
}
