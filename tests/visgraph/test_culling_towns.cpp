// Exact culling on towns of real-building shapes, against casting every
// pair (bit for bit: degree, S_S sums, distances, edges): a hillside terrain
// mesh with houses sunk into it, gabled roofs above the eaves, L-shaped
// houses, courtyard blocks, terraces of touching houses that share their
// party-wall corners (as CityJSON models do), a wall split where a lower
// neighbour meets it (a T-junction), and eye points on the lines that extend
// the walls (sight lines that graze a corner or run along a wall).  Every
// occluder the culling uses, for clusters or packet by packet, is exercised
// here at the margins that make it exact; an occluder taken wrongly (a wall
// or prism assumed to reach above its eave, a quad grown past its edges)
// changes some pair's answer in these scenes and fails the comparison.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
struct Town {
  Mesh mesh;
  std::vector<Vector3d> nodes;
  std::vector<std::array<double, 4>> footprints;  // x0, x1, y0, y1 of every building, to keep nodes out
};

// Hillside: z = slope x + a bump, on a grid of shared vertices (slope
// and bump 0: flat ground, where every eye stands at one height and the
// culling also works in the eyes' plane, src/eye_plane.hpp).
struct Hill {
  double slope, bump;
};
double ground(double x, double y, Hill hill) {
  return hill.slope * x + hill.bump * std::sin(0.11 * x) * std::cos(0.07 * y);
}

void add_terrain(Mesh& m, double size, double cell, Hill hill) {
  const auto g = static_cast<std::uint32_t>(m.add_group("terrain"));
  const int n = static_cast<int>(size / cell);
  const auto base = static_cast<std::uint32_t>(m.vertices.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i * cell, j * cell, ground(i * cell, j * cell, hill));
  const auto v = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      m.triangle_group.push_back(g);
      m.triangle_group.push_back(g);
    }
}

// A closed house over a polygon footprint (counter-clockwise, shared
// vertex indices): walls from `base` to `eave`, a flat roof, or for a
// rectangle a gable roof rising to `ridge` along x.  `extra` corners are
// inserted into the walls (a vertex where a neighbour's lower wall ends:
// the wall is split there, a T-junction for the neighbour).
void add_house(Mesh& m, const std::vector<Vector3d>& outline, double base, double eave, double ridge,
               const std::string& group) {
  const auto g = static_cast<std::uint32_t>(m.add_group(group));
  const std::size_t n = outline.size();
  const auto first = static_cast<std::uint32_t>(m.vertices.size());
  for (const Vector3d& p : outline) m.vertices.emplace_back(p.x(), p.y(), base);
  for (const Vector3d& p : outline) m.vertices.emplace_back(p.x(), p.y(), eave);
  const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m.triangles.push_back({a, b, c});
    m.triangle_group.push_back(g);
  };
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = first + static_cast<std::uint32_t>(k), b = first + static_cast<std::uint32_t>((k + 1) % n);
    tri(a, b, b + static_cast<std::uint32_t>(n));
    tri(a, b + static_cast<std::uint32_t>(n), a + static_cast<std::uint32_t>(n));
  }
  // Floor and roof as fans from vertex 0 (the outlines used are star-shaped
  // from their first corner).
  for (std::size_t k = 1; k + 1 < n; ++k) tri(first, first + static_cast<std::uint32_t>(k + 1), first + static_cast<std::uint32_t>(k));
  const auto top = first + static_cast<std::uint32_t>(n);
  if (ridge > eave && n == 4) {
    // Gable along x: ridge vertices above the middles of the y-extent.
    const Vector3d& p0 = outline[0];
    const Vector3d& p2 = outline[2];
    const double ym = 0.5 * (p0.y() + p2.y());
    const auto r0 = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(p0.x(), ym, ridge);
    m.vertices.emplace_back(p2.x(), ym, ridge);
    // outline: (x0,y0) (x1,y0) (x1,y1) (x0,y1)
    tri(top + 0, top + 1, r0 + 1);
    tri(top + 0, r0 + 1, r0);
    tri(top + 2, top + 3, r0);
    tri(top + 2, r0, r0 + 1);
    tri(top + 1, top + 2, r0 + 1);  // gable ends
    tri(top + 3, top + 0, r0);
  } else {
    for (std::size_t k = 1; k + 1 < n; ++k) tri(top, top + static_cast<std::uint32_t>(k), top + static_cast<std::uint32_t>(k + 1));
  }
}

std::vector<Vector3d> rectangle(double x0, double x1, double y0, double y1) {
  return {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
}

// A courtyard block: four closed wings around an open yard.
void add_courtyard(Mesh& m, double x0, double y0, double size, double wing, double base, double eave,
                   const std::string& group, Town& t) {
  const double x1 = x0 + size, y1 = y0 + size;
  add_house(m, rectangle(x0, x1, y0, y0 + wing), base, eave, eave, group);
  add_house(m, rectangle(x0, x1, y1 - wing, y1), base, eave, eave, group);
  add_house(m, rectangle(x0, x0 + wing, y0 + wing, y1 - wing), base, eave, eave, group);
  add_house(m, rectangle(x1 - wing, x1, y0 + wing, y1 - wing), base, eave, eave, group);
  t.footprints.push_back({x0, x1, y0, y0 + wing});
  t.footprints.push_back({x0, x1, y1 - wing, y1});
  t.footprints.push_back({x0, x0 + wing, y0, y1});
  t.footprints.push_back({x1 - wing, x1, y0, y1});
}

// A terrace of touching houses along x whose ground corners are shared
// vertices (indices), each house with its own eave and, every other one, a
// gable: where a lower house meets a taller one, the lower one's eave corner
// lies on the taller one's wall edge without splitting it (a T-junction, as
// in real models); the front facades are coplanar.
void add_terrace(Mesh& m, double x0, double y0, double width, double depth, int houses, double base,
                 std::mt19937_64& rng, Town& t) {
  std::uniform_real_distribution<double> eave_height(4.0, 9.0);
  const auto g = static_cast<std::uint32_t>(m.add_group("terrace"));
  const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m.triangles.push_back({a, b, c});
    m.triangle_group.push_back(g);
  };
  const auto ground_corner = static_cast<std::uint32_t>(m.vertices.size());  // (x_h, y0) and (x_h, y1) for h = 0..houses
  for (int h = 0; h <= houses; ++h) {
    m.vertices.emplace_back(x0 + h * width, y0, base);
    m.vertices.emplace_back(x0 + h * width, y0 + depth, base);
  }
  for (int h = 0; h < houses; ++h) {
    const double xa = x0 + h * width, xb = xa + width, e = eave_height(rng);
    const std::uint32_t a0 = ground_corner + 2 * static_cast<std::uint32_t>(h), a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
    const auto top = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(xa, y0, e);
    m.vertices.emplace_back(xb, y0, e);
    m.vertices.emplace_back(xb, y0 + depth, e);
    m.vertices.emplace_back(xa, y0 + depth, e);
    tri(a0, b0, top + 1), tri(a0, top + 1, top + 0);      // front
    tri(b1, a1, top + 3), tri(b1, top + 3, top + 2);      // back
    tri(b0, b1, top + 2), tri(b0, top + 2, top + 1);      // party wall (or end) at xb
    tri(a1, a0, top + 0), tri(a1, top + 0, top + 3);      // party wall (or end) at xa
    tri(a0, a1, b1), tri(a0, b1, b0);                     // floor
    if (h % 2) {
      const auto r = static_cast<std::uint32_t>(m.vertices.size());
      m.vertices.emplace_back(xa, y0 + depth / 2, e + 3);
      m.vertices.emplace_back(xb, y0 + depth / 2, e + 3);
      tri(top + 0, top + 1, r + 1), tri(top + 0, r + 1, r);
      tri(top + 2, top + 3, r), tri(top + 2, r, r + 1);
      tri(top + 1, top + 2, r + 1), tri(top + 3, top + 0, r);
    } else {
      tri(top + 0, top + 1, top + 2), tri(top + 0, top + 2, top + 3);
    }
    t.footprints.push_back({xa, xb, y0, y0 + depth});
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool inside_any(const Town& t, double x, double y) {
  for (const auto& f : t.footprints)
    if (x >= f[0] && x <= f[1] && y >= f[2] && y <= f[3]) return true;
  return false;
}

// One town, seeded: terrain, a courtyard block, a terrace, L-shaped and
// gabled houses; nodes on a grid and on the walls' extension lines.
Town make_town(std::uint64_t seed, Hill hill) {
  const double slope = hill.slope;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Town t;
  const double size = 64;
  add_terrain(t.mesh, size, 4.0, hill);
  // Houses stand from below the terrain (sunk into the slope) to eaves above it.
  add_courtyard(t.mesh, 6, 6, 20, 4, slope * 6 - 3, slope * 26 + 7 + 3 * unit(rng), "courtyard", t);
  add_terrace(t.mesh, 32, 10, 5.0, 8.0, 5, slope * 32 - 3, rng, t);
  // An L-shaped house (star-shaped from its first corner) and gabled houses.
  const std::vector<Vector3d> ell = {{36, 34, 0}, {50, 34, 0}, {50, 40, 0}, {42, 40, 0}, {42, 48, 0}, {36, 48, 0}};
  add_house(t.mesh, ell, slope * 36 - 3, slope * 50 + 6, slope * 50 + 6, "ell");
  t.footprints.push_back({36, 50, 34, 40});
  t.footprints.push_back({36, 42, 34, 48});
  for (int h = 0; h < 3; ++h) {
    const double x0 = 8 + 9 * h + 2 * unit(rng), y0 = 40 + 6 * unit(rng);
    add_house(t.mesh, rectangle(x0, x0 + 6, y0, y0 + 8), slope * x0 - 3, slope * (x0 + 6) + 4, slope * (x0 + 6) + 7,
              "gabled");
    t.footprints.push_back({x0, x0 + 6, y0, y0 + 8});
  }
  // Nodes 1.7 m over the terrain: a 3 m grid, and points on the lines that
  // extend the terrace's and courtyard's walls (x or y equal to a wall's).
  const auto eye = [&](double x, double y) { return Vector3d(x, y, ground(x, y, hill) + 1.7); };
  for (double y = 1.5; y < size; y += 3)
    for (double x = 1.5; x < size; x += 3)
      if (!inside_any(t, x, y)) t.nodes.push_back(eye(x, y));
  for (double x : {6.0, 10.0, 22.0, 26.0, 32.0, 37.0, 42.0, 57.0})
    for (double y : {2.0, 30.0, 31.0, 52.0, 60.0})
      if (!inside_any(t, x, y)) t.nodes.push_back(eye(x, y));
  for (double y : {6.0, 10.0, 18.0, 26.0, 34.0, 40.0})
    for (double x : {2.0, 29.0, 31.0, 55.0, 62.0})
      if (!inside_any(t, x, y)) t.nodes.push_back(eye(x, y));
  return t;
}

struct Outcome {
  vg::VisibilityResult result;
  std::vector<vg::Edge> edges;
};

Outcome run(const vg::Scene& scene, const std::vector<Vector3d>& nodes, bool culling, int threads) {
  vg::VisibilityOptions o;
  o.sigmas = {0.0, 1.5e-4, 0.0045, 0.02874311, 0.3};
  o.distance_stats = true;
  o.culling = culling;
  o.threads = threads;
  Outcome r;
  o.edge_sink = [&r](const std::vector<vg::Edge>& block) { r.edges.insert(r.edges.end(), block.begin(), block.end()); };
  r.result = vg::all_to_all(scene, nodes, o);
  return r;
}
}  // namespace

TEST_CASE("culling: hillside towns of real-building shapes, identical to casting every pair", "[visgraph][culling]") {
  // Trials 0-2 on hillsides; trial 3 on flat ground, where the eyes' plane
  // decides sight lines too (and must not change a single answer).
  for (int trial = 0; trial < 4; ++trial) {
    const Hill hill = trial == 3 ? Hill{0.0, 0.0} : Hill{0.08 * trial, 1.5};
    const Town town = make_town(1000 + static_cast<std::uint64_t>(trial), hill);
    const vg::Scene scene(town.mesh);
    INFO("trial " << trial << ", " << town.nodes.size() << " nodes, " << town.mesh.triangles.size() << " triangles");
    const Outcome brute = run(scene, town.nodes, false, 2);
    const Outcome culled = run(scene, town.nodes, true, 1 + trial % 2);
    const vg::VisibilityResult& b = brute.result;
    const vg::VisibilityResult& c = culled.result;
    CHECK(c.degree == b.degree);
    REQUIRE(c.sum.size() == b.sum.size());
    for (std::size_t k = 0; k < b.sum.size(); ++k) CHECK(same_bits(c.sum[k], b.sum[k]));
    CHECK(same_bits(c.mean_distance, b.mean_distance));
    CHECK(same_bits(c.max_distance, b.max_distance));
    CHECK(c.pairs_visible == b.pairs_visible);
    REQUIRE(culled.edges.size() == brute.edges.size());
    std::size_t differ = 0;
    for (std::size_t e = 0; e < brute.edges.size(); ++e)
      differ += culled.edges[e].i != brute.edges[e].i || culled.edges[e].j != brute.edges[e].j ||
                std::memcmp(&culled.edges[e].distance, &brute.edges[e].distance, sizeof(double)) != 0;
    CHECK(differ == 0);
    // The scenes exercise the culling (how much it decides is the
    // benchmark's business): some pairs blocked, some in sight, some cast.
    CHECK(c.pairs_culled_blocked > 0);
    CHECK(c.pairs_culled_visible > 0);
    CHECK(c.pairs_cast > 0);
    CHECK(c.pairs_cast < b.pairs_cast);
  }
}
