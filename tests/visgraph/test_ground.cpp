// The ground under buildings-only models (ground.hpp): base points from
// GroundSurfaces and from wall feet alike, the flat model's plane (the
// existing behaviour, bit for bit), and on the synthetic hillside town
// (hillside.hpp) the inferred TIN: every node on it within the linear
// interpolation bound of the true ground, no node under a building, and
// lines of sight that agree with an independent segment test.
#include "sight_check.hpp"

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/hillside.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {

// The mesh's triangles of one group.
std::vector<std::array<Vector3d, 3>> group_triangles(const Mesh& m, const std::string& group) {
  std::vector<std::array<Vector3d, 3>> out;
  const auto g = std::find(m.groups.begin(), m.groups.end(), group) - m.groups.begin();
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.triangle_group[t] == static_cast<std::uint32_t>(g))
      out.push_back({m.vertices[m.triangles[t][0]], m.vertices[m.triangles[t][1]], m.vertices[m.triangles[t][2]]});
  return out;
}

double cross2(const Vector3d& o, const Vector3d& a, const Vector3d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool inside_xy(const std::array<Vector3d, 3>& t, double x, double y, double slack = 1e-9) {
  const Vector3d p(x, y, 0);
  const double a = cross2(t[0], t[1], p), b = cross2(t[1], t[2], p), c = cross2(t[2], t[0], p);
  return (a >= -slack && b >= -slack && c >= -slack) || (a <= slack && b <= slack && c <= slack);
}

// Radius of the smallest circle holding a triangle's xy: half its longest
// side when its widest angle is not acute, its circumradius otherwise.
double enclosing_radius(const std::array<Vector3d, 3>& t) {
  const double a = (t[1] - t[2]).head<2>().norm(), b = (t[0] - t[2]).head<2>().norm(), c = (t[0] - t[1]).head<2>().norm();
  const double longest = std::max({a, b, c});
  if (2 * longest * longest >= a * a + b * b + c * c) return 0.5 * longest;  // right or obtuse
  const double area = 0.5 * std::abs(cross2(t[0], t[1], t[2]));
  return a * b * c / (4 * area);
}

}  // namespace

TEST_CASE("building bases come from GroundSurfaces, or else from the feet of vertical wall edges", "[visgraph][ground]") {
  const vg::HillsideOptions o;
  const Mesh town = vg::hillside_town(o);
  const vg::BuildingBases with_classes = vg::building_bases(town);
  // 5 x 5 blocks of 4 buildings, each footprint 4 corners on the true ground.
  CHECK(with_classes.building_base.size() == 100);
  CHECK(with_classes.from_ground_surface == 100);
  CHECK(with_classes.points.size() == 400);
  for (const Vector3d& p : with_classes.points) CHECK(p.z() == vg::hillside_ground(o, p.x(), p.y()));
  // The same model as an OBJ would give it (no classes): the walls' feet.
  Mesh plain = town;
  plain.triangle_class.clear();
  plain.classes.clear();
  const vg::BuildingBases from_walls = vg::building_bases(plain);
  CHECK(from_walls.from_walls == 100);
  CHECK(from_walls.points == with_classes.points);
  // A building of one sloping triangle (neither): its lowest vertex.
  Mesh blob;
  add_triangle(blob, {0, 0, 3}, {4, 0, 5}, {0, 4, 7}, "blob");
  const vg::BuildingBases lowest = vg::building_bases(blob);
  CHECK(lowest.from_lowest_vertex == 1);
  REQUIRE(lowest.points.size() == 1);
  CHECK(lowest.points[0] == Vector3d(0, 0, 3));
}

TEST_CASE("a flat model keeps its plane at the lowest z, and a plane under floating bases is refused or counted", "[visgraph][ground]") {
  // solid_lods_hole_v1.1: one house, base at z = 0.
  const std::string house = std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/cityjson/solid_lods_hole_v1.1.city.json";
  Mesh m = vg::load_cityjson(house);
  Mesh plane = m;
  vg::add_ground_plane(plane);
  const vg::GroundMade made = vg::add_ground(m, {});
  CHECK_FALSE(made.inferred);
  CHECK(made.plane_z == 0.0);
  // The same vertices and triangles as the plane the model always got.
  CHECK(m.vertices == plane.vertices);
  CHECK(m.triangles == plane.triangles);
  CHECK(m.classes == plane.classes);

  const vg::HillsideOptions o;
  Mesh town = vg::hillside_town(o);
  vg::GroundRequest lowest;
  lowest.rule = vg::GroundRule::lowest_plane;
  CHECK_THROWS_WITH(vg::add_ground(town, lowest), Catch::Contains("would leave eye points below") &&
                                                       Catch::Contains("the bases of the 100 buildings lie from"));
  vg::GroundRequest at;
  at.rule = vg::GroundRule::plane_at;
  at.plane_z = 20.0;
  const vg::GroundMade counted = vg::add_ground(town, at);
  // Buildings whose lowest corner stands more than 1.7 m above z = 20.
  std::size_t expected = 0;
  for (double base : vg::building_bases(vg::hillside_town(o)).building_base) expected += base > 21.7;
  CHECK(counted.floating == expected);
  CHECK(expected > 10);
}

TEST_CASE("the inferred ground is the Delaunay triangulation of the base points", "[visgraph][ground]") {
  const vg::HillsideOptions o;
  Mesh town = vg::hillside_town(o);
  const vg::BuildingBases bases = vg::building_bases(town);
  const vg::GroundMade made = vg::add_ground(town, {});
  REQUIRE(made.inferred);
  CHECK(made.buildings == 100);
  CHECK_THAT(made.description, Catch::Contains("inferred from 100 building bases"));
  const auto tin = group_triangles(town, vg::kInferredGroundGroup);
  CHECK(tin.size() == made.triangles);
  // Every triangle faces up, and no base point lies inside its circumcircle
  // (the empty-circle property that defines the Delaunay triangulation,
  // checked by the in-circle determinant against every point).
  std::size_t violations = 0;
  for (const auto& t : tin) {
    CHECK(cross2(t[0], t[1], t[2]) > 0);
    for (const Vector3d& p : bases.points) {
      const auto lift = [&](const Vector3d& q) {
        const double dx = q.x() - p.x(), dy = q.y() - p.y();
        return Eigen::Vector3d(dx, dy, dx * dx + dy * dy);
      };
      const double det = lift(t[0]).dot(lift(t[1]).cross(lift(t[2])));
      const double scale = lift(t[0]).norm() * lift(t[1]).norm() * lift(t[2]).norm();
      violations += det > 1e-9 * scale;
    }
  }
  CHECK(violations == 0);
  // Euler: a triangulation of n points with h on the hull has 2n - 2 - h triangles.
  CHECK(tin.size() <= 2 * bases.points.size() - 5);
}

// The hillside town on its inferred ground, with nodes on a 2 m grid.
struct HillsideRun {
  vg::HillsideOptions options;
  Mesh buildings = vg::hillside_town(options);
  Mesh town = with_ground(buildings);
  vg::Scene scene{town};
  std::vector<Vector3d> eyes = nodes(scene);

  static Mesh with_ground(Mesh m) {
    vg::add_ground(m, {});
    return m;
  }
  static std::vector<Vector3d> nodes(const vg::Scene& scene) {
    vg::NodeGridOptions grid;
    grid.spacing = 2.0;
    const vg::NodeSet set = vg::generate_nodes(scene, grid);
    CHECK(set.elevated == 0);
    return set.eyes;
  }
};

TEST_CASE("on the hillside town every node stands on the inferred ground, none under a building", "[visgraph][ground]") {
  const HillsideRun run;
  REQUIRE(run.eyes.size() > 5000);
  const auto tin = group_triangles(run.town, vg::kInferredGroundGroup);
  std::vector<std::vector<std::array<Vector3d, 3>>> roofs;
  for (std::size_t b = 0; b < 100; ++b) roofs.push_back(group_triangles(run.buildings, "building-" + std::to_string(b)));
  const double M = vg::hillside_curvature_bound(run.options);
  double worst = 0, worst_bound = 0, sum = 0;
  std::size_t under = 0, beyond_bound = 0;
  for (const Vector3d& e : run.eyes) {
    const double error = e.z() - 1.7 - vg::hillside_ground(run.options, e.x(), e.y());
    // The TIN triangle under the node bounds its error: M R^2 / 2
    // (hillside.hpp), plus 1 mm for Embree's single-precision hit.
    double bound = -1;
    for (const auto& t : tin)
      if (inside_xy(t, e.x(), e.y())) bound = std::max(bound, 0.5 * M * std::pow(enclosing_radius(t), 2));
    REQUIRE(bound >= 0);
    beyond_bound += std::abs(error) > bound + 1e-3;
    worst = std::max(worst, std::abs(error));
    worst_bound = std::max(worst_bound, bound);
    sum += std::abs(error);
    for (const auto& roof : roofs)
      for (const auto& t : roof) under += inside_xy(t, e.x(), e.y(), -1e-9);
  }
  CHECK(beyond_bound == 0);
  CHECK(under == 0);
  WARN("hillside town, 2 m grid: " << run.eyes.size() << " nodes; ground error max " << worst << " m, mean "
                                   << sum / run.eyes.size() << " m (largest bound " << worst_bound << " m)");
  // And the flat plane the model used to get: eyes under most buildings'
  // bases (lowest corner more than 1.7 m above the lowest z).
  std::size_t floating = 0;
  const double lowest = vg::mesh_stats(run.buildings).lower.z();
  for (double base : vg::building_bases(run.buildings).building_base) floating += base - lowest > 1.7;
  CHECK(floating > 80);
}

TEST_CASE("lines of sight over the hillside town agree with an independent segment test", "[visgraph][ground]") {
  const HillsideRun run;
  const SightCheck check = random_sight_lines(run.scene, run.town, run.buildings, run.eyes, 3, 60, 30);
  for (const std::string& d : check.disagreements) FAIL_CHECK(d);
  CHECK(check.agree == check.pairs);
  // Both outcomes are common, and the ground itself hides some pairs (over
  // the ridge), so the test exercises the TIN as an occluder.
  CHECK(check.visible > check.pairs / 20);
  CHECK(check.pairs - check.visible > check.pairs / 20);
  CHECK(check.hidden_by_ground > 0);
  WARN("hillside town: " << check.pairs << " random pairs, " << check.visible << " visible, " << check.hidden_by_ground
                         << " hidden by the ground alone; Embree agrees with the segment test on " << check.agree);
}
