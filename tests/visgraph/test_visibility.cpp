// Visibility and contrast-ratio scores: geometric cases whose answer is known,
// an independent brute-force evaluation (double-precision segment–triangle
// tests, no Embree), symmetry, thread-count independence and the pruning bound.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
// Fixed-point rounding: each contribution is rounded to 2^-41 (see
// visibility.hpp), plus double evaluation of exp (~2 ulp of C <= 1).
double sum_tolerance(std::uint32_t partners) { return partners * (std::ldexp(1.0, -41) + 4e-16) + 1e-15; }

vg::VisibilityOptions with_sigmas(std::vector<double> sigmas) {
  vg::VisibilityOptions o;
  o.sigmas = std::move(sigmas);
  return o;
}

Mesh random_scene(std::mt19937_64& rng, std::vector<Vector3d>& nodes, int boxes, int count) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Mesh m;
  add_floor(m, 0, 30, 0, 30, 0, "floor");
  for (int b = 0; b < boxes; ++b) {
    const double x = 30 * u(rng), y = 30 * u(rng), w = 1 + 5 * u(rng), d = 1 + 5 * u(rng), h = 1 + 4 * u(rng);
    add_box(m, {x, y, 0}, {x + w, y + d, h}, "obstacle");
  }
  nodes.clear();
  for (int i = 0; i < count; ++i) nodes.emplace_back(30 * u(rng), 30 * u(rng), 0.5 + 3.5 * u(rng));
  return m;
}
}  // namespace

TEST_CASE("open floor: every node sees every other node", "[visgraph][visibility]") {
  Mesh m;
  add_floor(m, 0, 20, 0, 20, 0, "floor");
  const vg::Scene scene(m);
  const auto nodes = grid_points(0, 20, 0, 20, 2, 1.7);  // 100 nodes
  const std::vector<double> sigmas = {0.0, 0.01, 0.5};
  const vg::VisibilityResult r = vg::all_to_all(scene, nodes, with_sigmas(sigmas));
  REQUIRE(r.degree.size() == nodes.size());
  for (std::uint32_t d : r.degree) CHECK(d == nodes.size() - 1);
  CHECK(r.pairs_visible == nodes.size() * (nodes.size() - 1) / 2);
  // sigma = 0: C = 1 for every pair, so S_S = degree exactly; S_A = 1.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    CHECK(r.sum[0][i] == Approx(nodes.size() - 1).margin(0));
    CHECK(r.average(0, i) == 1.0);
  }
  // Other sigmas: against sums of std::exp in long double.
  const BruteForce bf = brute_force_all_pairs(m, nodes, sigmas);
  for (std::size_t k = 1; k < sigmas.size(); ++k)
    for (std::size_t i = 0; i < nodes.size(); ++i)
      CHECK(std::abs(r.sum[k][i] - static_cast<double>(bf.sum[k][i])) <= sum_tolerance(r.degree[i]));
}

TEST_CASE("a wall between two halves: nodes see only their own half", "[visgraph][visibility]") {
  Mesh m;
  add_floor(m, 0, 20, 0, 10, 0, "floor");
  add_box(m, {9.9, -1, 0}, {10.1, 11, 5}, "wall");  // taller than any eye, wider than the floor
  const vg::Scene scene(m);
  const auto nodes = grid_points(0, 20, 0, 10, 1, 1.7);  // 100 per half
  const vg::VisibilityResult r = vg::all_to_all(scene, nodes, with_sigmas({0.1}));
  for (std::size_t i = 0; i < nodes.size(); ++i) CHECK(r.degree[i] == 99u);
  CHECK(r.pairs_visible == 2u * (100 * 99 / 2));
}

TEST_CASE("a room with a door: sight lines pass only through the opening", "[visgraph][visibility]") {
  // Room [0,10]^2, walls 0.2 m thick and 3 m tall, flat roof, and a door 2 m
  // wide (x in [4,6]) and 2.5 m tall in the wall at y = 0.
  Mesh m;
  add_floor(m, -20, 30, -20, 30, 0, "floor");
  add_box(m, {0, 9.8, 0}, {10, 10, 3}, "wall");
  add_box(m, {0, 0.2, 0}, {0.2, 9.8, 3}, "wall");
  add_box(m, {9.8, 0.2, 0}, {10, 9.8, 3}, "wall");
  add_box(m, {0, 0, 0}, {4, 0.2, 3}, "wall");
  add_box(m, {6, 0, 0}, {10, 0.2, 3}, "wall");
  add_box(m, {4, 0, 2.5}, {6, 0.2, 3}, "wall");  // lintel
  add_floor(m, 0, 10, 0, 10, 3, "roof");
  const vg::Scene scene(m);
  const std::vector<Vector3d> nodes = {
      {5, 5, 1.7},   // 0 inside, centre
      {1, 1, 1.7},   // 1 inside, corner
      {5, -5, 1.7},  // 2 outside, in front of the door
      {6.5, -5, 1.7},  // 3 outside, off to the side
      {5, 15, 1.7},  // 4 outside, behind the back wall
  };
  const vg::VisibilityResult r = vg::all_to_all(scene, nodes, with_sigmas({0.0}));
  // Geometry: 0-1 same room; 0-2 straight through the door; 1-3 crosses the
  // wall slab y in [0, 0.2] at x in [1.73, 1.92] (wall); 0-3 crosses it at
  // x in [5.72, 5.75] (door); 2-3 open ground; 4 is behind the back wall from
  // 0 and 1, and the lines 4-2, 4-3 enter through the door but meet the back wall.
  CHECK(r.degree[0] == 3u);  // 1, 2, 3
  CHECK(r.degree[1] == 1u);  // 0
  CHECK(r.degree[2] == 2u);  // 0, 3
  CHECK(r.degree[3] == 2u);  // 0, 2
  CHECK(r.degree[4] == 0u);
  CHECK(std::isnan(r.average(0, 4)));
  // And the brute-force evaluation agrees pair by pair.
  const BruteForce bf = brute_force_all_pairs(m, nodes, {0.0});
  for (std::size_t i = 0; i < nodes.size(); ++i) CHECK(r.degree[i] == bf.degree[i]);
}

TEST_CASE("S_S matches a brute-force evaluation on random scenes", "[visgraph][visibility]") {
  std::mt19937_64 rng(20211);
  const std::vector<double> sigmas = {0.0, 0.003, 0.05, 0.3, 2.0};
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<Vector3d> nodes;
    const Mesh m = random_scene(rng, nodes, 8, 150);
    const vg::Scene scene(m);
    vg::VisibilityOptions o = with_sigmas(sigmas);
    o.distance_stats = true;
    const vg::VisibilityResult r = vg::all_to_all(scene, nodes, o);
    const BruteForce bf = brute_force_all_pairs(m, nodes, sigmas);
    std::size_t some_blocked = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      INFO("trial " << trial << " node " << i);
      REQUIRE(r.degree[i] == bf.degree[i]);
      some_blocked += bf.degree[i] < nodes.size() - 1;
      for (std::size_t k = 0; k < sigmas.size(); ++k)
        CHECK(std::abs(r.sum[k][i] - static_cast<double>(bf.sum[k][i])) <= sum_tolerance(r.degree[i]));
    }
    CHECK(some_blocked > 0);  // the scene is not trivially open
  }
}

TEST_CASE("the graph is symmetric: i->j and j->i agree", "[visgraph][visibility]") {
  std::mt19937_64 rng(7);
  std::vector<Vector3d> nodes;
  const Mesh m = random_scene(rng, nodes, 10, 200);
  const vg::Scene scene(m);
  const vg::VisibilityResult all = vg::all_to_all(scene, nodes, with_sigmas({0.02}));
  // to_targets casts every ordered pair, each from its own source: both
  // directions of every pair are decided independently.
  const vg::VisibilityResult directed = vg::to_targets(scene, nodes, nodes, with_sigmas({0.02}));
  std::uint64_t degree_sum = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    CHECK(all.degree[i] == directed.degree[i]);
    CHECK(all.sum[0][i] == directed.sum[0][i]);  // same integer sums
    degree_sum += all.degree[i];
  }
  CHECK(degree_sum == 2 * all.pairs_visible);
  CHECK(directed.coincident_pairs == nodes.size());  // each node against itself

  // The edge list holds each visible unordered pair once, i < j, grouped by
  // the end the pair is cast from (visibility.hpp), in increasing x of that end.
  vg::VisibilityOptions o = with_sigmas({0.02});
  std::vector<vg::Edge> edges;
  o.edge_sink = [&](const std::vector<vg::Edge>& block) { edges.insert(edges.end(), block.begin(), block.end()); };
  // x of the end a pair is cast from: the smaller x (random nodes: no ties).
  const auto cast_end_x = [&](const vg::Edge& e) { return std::min(nodes[e.i].x(), nodes[e.j].x()); };
  const vg::VisibilityResult with_edges = vg::all_to_all(scene, nodes, o);
  REQUIRE(edges.size() == all.pairs_visible);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    CHECK(edges[e].i < edges[e].j);
    if (e) CHECK(cast_end_x(edges[e - 1]) <= cast_end_x(edges[e]));
    CHECK(edges[e].distance == Approx((nodes[edges[e].i] - nodes[edges[e].j]).norm()).epsilon(1e-12));
  }
  CHECK(with_edges.sum[0] == all.sum[0]);
}

TEST_CASE("results are identical on 1 and 2 threads", "[visgraph][visibility]") {
  std::mt19937_64 rng(99);
  std::vector<Vector3d> nodes;
  const Mesh m = random_scene(rng, nodes, 10, 600);
  const vg::Scene scene(m);
  vg::VisibilityOptions o = with_sigmas({0.0, 0.01, 0.1, 1.0});
  o.distance_stats = true;
  o.threads = 1;
  const vg::VisibilityResult one = vg::all_to_all(scene, nodes, o);
  o.threads = 2;
  const vg::VisibilityResult two = vg::all_to_all(scene, nodes, o);
  CHECK(one.degree == two.degree);
  CHECK(one.sum == two.sum);  // bit-identical
  // Bit-identical, NaN (degree 0) included: compare the bytes.
  const auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  CHECK(same_bits(one.mean_distance, two.mean_distance));
  CHECK(same_bits(one.max_distance, two.max_distance));
  CHECK(one.pairs_cast == two.pairs_cast);
}

TEST_CASE("range pruning stays within its certified bound", "[visgraph][visibility]") {
  std::mt19937_64 rng(5);
  std::vector<Vector3d> nodes;
  Mesh m = random_scene(rng, nodes, 6, 400);
  const vg::Scene scene(m);
  const std::vector<double> sigmas = {0.2, 0.5};
  vg::VisibilityOptions every_pair = with_sigmas(sigmas);
  every_pair.culling = false;  // pairs_cast below compares rays with rays
  const vg::VisibilityResult exact = vg::all_to_all(scene, nodes, every_pair);
  for (double eps : {1e-1, 1e-2, 1e-3}) {
    vg::VisibilityOptions o = with_sigmas(sigmas);
    o.prune_below = eps;
    o.always_prune = true;  // the pruning machinery itself, even where exact is faster
    const vg::VisibilityResult pruned = vg::all_to_all(scene, nodes, o);
    INFO("eps " << eps);
    CHECK(pruned.pruning_radius == Approx(std::log(1 / eps) / 0.2));
    CHECK_FALSE(pruned.degree_exact);
    CHECK(pruned.degree.empty());
    CHECK(pruned.pairs_cast < exact.pairs_cast);
    std::size_t bounded_nodes = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      bounded_nodes += pruned.pruned[i] > 0;
      for (std::size_t k = 0; k < sigmas.size(); ++k) {
        const double error = exact.sum[k][i] - pruned.sum[k][i];
        CHECK(error >= -sum_tolerance(exact.degree[i]));  // pruning only removes terms
        CHECK(error <= pruned.sum_error_bound(i) + sum_tolerance(exact.degree[i]));
      }
    }
    CHECK(bounded_nodes > 0);
  }
  // sigma = 0 ("no extinction") disables pruning: nothing can be skipped.
  vg::VisibilityOptions o = with_sigmas({0.0, 0.5});
  o.prune_below = 1e-3;
  o.always_prune = true;
  const vg::VisibilityResult none = vg::all_to_all(scene, nodes, o);
  CHECK(none.degree_exact);
  CHECK(std::isinf(none.pruning_radius));
}

TEST_CASE("max distance limits lines of sight and keeps degree exact", "[visgraph][visibility]") {
  Mesh m;
  add_floor(m, 0, 20, 0, 20, 0, "floor");
  const vg::Scene scene(m);
  const auto nodes = grid_points(0, 20, 0, 20, 1, 1.7);
  vg::VisibilityOptions o = with_sigmas({0.1});
  o.max_distance = 3.0;
  const vg::VisibilityResult r = vg::all_to_all(scene, nodes, o);
  REQUIRE(r.degree_exact);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::uint32_t expected = 0;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      expected += j != i && (nodes[j] - nodes[i]).norm() <= 3.0;
    CHECK(r.degree[i] == expected);
  }
}

TEST_CASE("UTM-sized coordinates give the same graph as local ones", "[visgraph][visibility]") {
  std::mt19937_64 rng(11);
  std::vector<Vector3d> nodes;
  const Mesh local = random_scene(rng, nodes, 8, 150);
  const Vector3d offset(512345.25, 4123456.5, 312.0);
  Mesh far = local;
  for (Vector3d& v : far.vertices) v += offset;
  std::vector<Vector3d> far_nodes = nodes;
  for (Vector3d& p : far_nodes) p += offset;
  const vg::Scene a(local), b(far);
  CHECK((b.origin() - a.origin() - offset).norm() < 1e-9);
  const vg::VisibilityResult ra = vg::all_to_all(a, nodes, with_sigmas({0.05}));
  const vg::VisibilityResult rb = vg::all_to_all(b, far_nodes, with_sigmas({0.05}));
  CHECK(ra.degree == rb.degree);
  for (std::size_t i = 0; i < nodes.size(); ++i) CHECK(std::abs(ra.sum[0][i] - rb.sum[0][i]) < 1e-9);
}

TEST_CASE("coincident nodes never reach Embree and are not lines of sight", "[visgraph][visibility]") {
  Mesh m;
  add_floor(m, 0, 10, 0, 10, 0, "floor");
  const vg::Scene scene(m);
  const std::vector<Vector3d> nodes = {{1, 1, 1.7}, {1, 1, 1.7}, {5, 5, 1.7}, {5, 5, 1.7 + 1e-5}};
  vg::VisibilityOptions every_pair = with_sigmas({0.0});
  every_pair.culling = false;  // an open floor: culling would decide every pair without rays
  const vg::VisibilityResult r = vg::all_to_all(scene, nodes, every_pair);
  CHECK(r.coincident_pairs == 1);
  CHECK(r.degree == std::vector<std::uint32_t>{2, 2, 3, 3});
  CHECK(r.pairs_cast == 4);  // 0-2, 0-3, 1-2, 1-3; 2-3 is 1e-5 m apart: visible without a ray
}

TEST_CASE("bad inputs are rejected with a clear error", "[visgraph][visibility]") {
  Mesh empty;
  CHECK_THROWS_WITH(vg::Scene(empty), Catch::Contains("empty"));
  Mesh nan_mesh;
  add_floor(nan_mesh, 0, 1, 0, 1, 0, "floor");
  nan_mesh.vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(vg::Scene(nan_mesh), Catch::Contains("vertex 2"));
  Mesh bad_index;
  add_floor(bad_index, 0, 1, 0, 1, 0, "floor");
  bad_index.triangles[0][2] = 99;
  CHECK_THROWS_WITH(vg::Scene(bad_index), Catch::Contains("missing vertex"));

  Mesh m;
  add_floor(m, 0, 10, 0, 10, 0, "floor");
  const vg::Scene scene(m);
  const std::vector<Vector3d> ok = {{1, 1, 1}, {2, 2, 1}};
  std::vector<Vector3d> nan_node = ok;
  nan_node[1].z() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(vg::all_to_all(scene, nan_node, with_sigmas({0.1})), Catch::Contains("node 2"));
  CHECK_THROWS_WITH(vg::all_to_all(scene, ok, with_sigmas({-1.0})), Catch::Contains("sigma"));
  CHECK_THROWS_WITH(vg::all_to_all(scene, {}, with_sigmas({0.1})), Catch::Contains("no nodes"));
  CHECK_THROWS_WITH(vg::to_targets(scene, ok, {}, with_sigmas({0.1})), Catch::Contains("no targets"));
  vg::VisibilityOptions o = with_sigmas({0.1});
  o.prune_below = 2;
  CHECK_THROWS_WITH(vg::all_to_all(scene, ok, o), Catch::Contains("tolerance"));
}
