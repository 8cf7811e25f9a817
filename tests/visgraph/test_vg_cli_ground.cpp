// `attenuvis vg` on a hilly model published as buildings only (the
// synthetic hillside town, written by the test as CityJSON and as OBJ): by
// default the nodes stand on the ground inferred from the building bases,
// within the interpolation bound of the true ground and never under a
// building; the run says where its ground came from; a plane at the lowest z
// is refused with the spread of the bases and the alternatives.
#include "city_files.hpp"
#include "cli_test_support.hpp"

#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/hillside.hpp>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

using namespace clitest;
using Catch::Matchers::Contains;
namespace vg = attenuvis::visgraph;

namespace {

// The largest M R^2 / 2 over the TIN's triangles (hillside.hpp): no node's
// ground may be further than this from the true ground.
double largest_interpolation_bound(const vg::HillsideOptions& o) {
  vg::Mesh town = vg::hillside_town(o);
  vg::add_ground(town, {});
  const auto g = static_cast<std::uint32_t>(
      std::find(town.groups.begin(), town.groups.end(), vg::kInferredGroundGroup) - town.groups.begin());
  double worst = 0;
  for (std::size_t t = 0; t < town.triangles.size(); ++t) {
    if (town.triangle_group[t] != g) continue;
    const auto& p = town.vertices[town.triangles[t][0]];
    const auto& q = town.vertices[town.triangles[t][1]];
    const auto& r = town.vertices[town.triangles[t][2]];
    // The circumradius bounds the smallest enclosing circle's radius.
    const double a = (q - r).head<2>().norm(), b = (p - r).head<2>().norm(), c = (p - q).head<2>().norm();
    const double area = 0.5 * std::abs((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
    worst = std::max(worst, 0.5 * vg::hillside_curvature_bound(o) * std::pow(a * b * c / (4 * area), 2));
  }
  return worst;
}

// Whether (x, y) lies inside a building's roof outline (its footprint).
bool under_a_building(const vg::Mesh& town, double x, double y) {
  const auto roof = std::find(town.classes.begin(), town.classes.end(), "RoofSurface") - town.classes.begin();
  for (std::size_t t = 0; t < town.triangles.size(); ++t) {
    if (town.triangle_class[t] != static_cast<std::uint32_t>(roof)) continue;
    const auto& p = town.vertices[town.triangles[t][0]];
    const auto& q = town.vertices[town.triangles[t][1]];
    const auto& r = town.vertices[town.triangles[t][2]];
    const auto side = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
    };
    if (side(p, q) > 0 && side(q, r) > 0 && side(r, p) > 0) return true;
  }
  return false;
}

void write_obj(const std::string& path, const vg::Mesh& mesh) {
  std::ofstream out(path);
  out.precision(17);
  for (const auto& v : mesh.vertices) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    out << "g " << mesh.groups[g] << "\n";
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (mesh.triangle_group[t] == g)
        out << "f " << mesh.triangles[t][0] + 1 << " " << mesh.triangles[t][1] + 1 << " " << mesh.triangles[t][2] + 1 << "\n";
  }
}

void check_nodes_on_true_ground(const Csv& csv, const vg::HillsideOptions& o, const vg::Mesh& town) {
  const double bound = largest_interpolation_bound(o) + 1e-3;  // + Embree's single-precision hit
  const std::size_t x = csv.column("x"), y = csv.column("y"), z = csv.column("z");
  std::size_t off = 0, under = 0;
  for (const auto& row : csv.rows) {
    off += std::abs(row[z] - 1.7 - vg::hillside_ground(o, row[x], row[y])) > bound;
    under += under_a_building(town, row[x], row[y]);
  }
  CHECK(off == 0);
  CHECK(under == 0);
}

}  // namespace

TEST_CASE("vg on a hilly buildings-only CityJSON stands the nodes on the inferred ground", "[visgraph][cli][ground]") {
  TempDir dir;
  const vg::HillsideOptions o;
  const vg::Mesh town = vg::hillside_town(o);
  vgtest::write_cityjson(dir / "town.city.json", town, "urn:ogc:def:crs:EPSG::32632");
  Run r = run("vg " + (dir / "town.city.json") + " --conditions clear --spacing 4 --out " + (dir / "n.csv") +
              " --summary " + (dir / "s.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("no ground") && Contains("ground: a TIN inferred from 100 building bases") &&
                           Contains("InferredGround"));
  const Csv csv = read_csv(dir / "n.csv");
  CHECK(csv.rows.size() > 1500);
  check_nodes_on_true_ground(csv, o, town);
  std::ifstream summary(dir / "s.json");
  const auto s = nlohmann::json::parse(summary);
  CHECK_THAT(s["scene"]["ground"].get<std::string>(), Contains("inferred from 100 building bases"));
  CHECK(s["node_grid"]["elevated_nodes"] == 0);

  // A plane at the lowest z would put eyes under the buildings: refused,
  // with the spread of the bases and the other grounds.
  r = run("vg " + (dir / "town.city.json") + " --conditions clear --spacing 4 --ground-plane yes --out " +
          (dir / "p.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("attenuvis: error:") && Contains("would leave eye points below") &&
                           Contains("the bases of the 100 buildings lie from") && Contains("--terrain DEM") &&
                           Contains("--ground-plane Z"));
  CHECK_FALSE(std::filesystem::exists(dir / "p.csv"));
  // A plane at a height the user names is taken, with a count of the
  // buildings it leaves floating.
  r = run("vg " + (dir / "town.city.json") + " --conditions clear --spacing 4 --ground-plane 20 --out " +
          (dir / "q.csv"));
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Contains("buildings stand more than the eye height above the ground plane at z = 20 m") &&
                           Contains("ground: a horizontal ground plane at z = 20 m (as asked)"));
  r = run("vg " + (dir / "town.city.json") + " --conditions clear --ground-plane uphill --out " + (dir / "u.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("--ground-plane: expected auto, yes, no or a height in metres, got 'uphill'"));
}

TEST_CASE("vg on the same town as OBJ (no classes) infers the ground from the walls' feet", "[visgraph][cli][ground]") {
  TempDir dir;
  const vg::HillsideOptions o;
  const vg::Mesh town = vg::hillside_town(o);
  write_obj(dir / "town.obj", town);
  const Run r = run("vg " + (dir / "town.obj") + " --conditions clear --spacing 4 --out " + (dir / "n.csv"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("ground: a TIN inferred from 100 building bases") && Contains("inferred-ground"));
  check_nodes_on_true_ground(read_csv(dir / "n.csv"), o, town);
}
