// CityJSON reading (visgraph/src/cityjson.cpp) on small files written for
// these tests (tests/data/visgraph/cityjson/, geometry described below with
// each expected count), plus the real Delfshaven file when it is present.
// Expected triangle counts follow from ear clipping: a simple n-gon gives
// n - 2 triangles, a quad with one quad hole 8.
#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/detail/polygon.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

namespace vg = attenuvis::visgraph;
using Eigen::Vector3d;

namespace {
std::string data(const std::string& name) { return std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/cityjson/" + name; }

std::string load_error(const std::string& path, const vg::CityJsonOptions& options = {}) {
  try {
    vg::load_cityjson(path, options);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

// Triangles and xy-projected area per class.
struct ClassTally {
  std::map<std::string, std::size_t> triangles;
  std::map<std::string, double> area;
};
ClassTally tally(const vg::Mesh& m) {
  ClassTally t;
  REQUIRE(m.triangle_class.size() == m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const std::string& c = m.classes[m.triangle_class[i]];
    ++t.triangles[c];
    const Vector3d& a = m.vertices[m.triangles[i][0]];
    const Vector3d& b = m.vertices[m.triangles[i][1]];
    const Vector3d& d = m.vertices[m.triangles[i][2]];
    t.area[c] += 0.5 * ((b - a).cross(d - a)).norm();
  }
  return t;
}
}  // namespace

TEST_CASE("polygon triangulation: concave outline, holes, repeats and degenerate rings", "[visgraph][cityjson]") {
  // L-shaped hexagon, area 10*10 - 6*6 = 64: 4 triangles of total area 64.
  const std::vector<Vector3d> L = {{0, 0, 0}, {10, 0, 0}, {10, 4, 0}, {4, 4, 0}, {4, 10, 0}, {0, 10, 0}};
  auto r = vg::triangulate_polygon({L});
  CHECK(r.status == vg::PolygonStatus::ok);
  REQUIRE(r.triangles.size() == 4);
  double area = 0;
  for (const auto& t : r.triangles) {
    const Vector3d n = (L[t[1]] - L[t[0]]).cross(L[t[2]] - L[t[0]]);
    CHECK(n.z() > 0);  // the outline's (counter-clockwise) orientation is kept
    area += 0.5 * n.norm();
  }
  CHECK(area == Approx(64).epsilon(1e-12));
  // A vertical 10 x 8 wall with a 3 x 2 window: 8 triangles, area 80 - 6 = 74.
  const std::vector<Vector3d> wall = {{0, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}};
  const std::vector<Vector3d> window = {{3, 0, 2}, {3, 0, 4}, {6, 0, 4}, {6, 0, 2}};
  r = vg::triangulate_polygon({wall, window});
  CHECK(r.status == vg::PolygonStatus::ok);
  CHECK(r.triangles.size() == 8);
  std::vector<Vector3d> all = wall;
  all.insert(all.end(), window.begin(), window.end());
  area = 0;
  for (const auto& t : r.triangles) area += 0.5 * (all[t[1]] - all[t[0]]).cross(all[t[2]] - all[t[0]]).norm();
  CHECK(area == Approx(74).epsilon(1e-12));
  // Collinear corners and repeats make no zero-area triangle.
  r = vg::triangulate_polygon({{{0, 0, 0}, {5, 0, 0}, {5, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {0, 0, 0}}});
  CHECK(r.status == vg::PolygonStatus::ok);
  CHECK(r.triangles.size() == 2);
  CHECK(vg::triangulate_polygon({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}).status == vg::PolygonStatus::degenerate);
  CHECK(vg::triangulate_polygon({{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}}).status == vg::PolygonStatus::degenerate);
  CHECK(vg::triangulate_polygon({}).status == vg::PolygonStatus::degenerate);
}

TEST_CASE("CityJSON 1.0: transform, semantics, object types, CRS", "[visgraph][cityjson]") {
  // A 10 x 10 x 6 m box building (MultiSurface: ground, roof, 4 walls) on a
  // 30 x 30 m TINRelief (2 triangles) beside a 30 x 3 m Road strip (1 quad); integer
  // vertices x 0.01 + (100000, 400000, 0).
  vg::CityJsonReport report;
  const vg::Mesh m = vg::load_cityjson(data("box_on_terrain_v1.0.city.json"), {}, &report);
  CHECK(report.version == "1.0");
  CHECK(report.city_objects == 3);
  CHECK(m.crs == "urn:ogc:def:crs:EPSG::28992");
  CHECK(vg::short_crs_name(m.crs) == "EPSG:28992");
  CHECK(m.triangles.size() == 16);
  CHECK(m.groups == std::vector<std::string>{"building-1", "terrain", "road-1"});
  const ClassTally t = tally(m);
  CHECK(t.triangles.at("RoofSurface") == 2);
  CHECK(t.triangles.at("GroundSurface") == 2);
  CHECK(t.triangles.at("WallSurface") == 8);
  CHECK(t.triangles.at("TINRelief") == 2);
  CHECK(t.triangles.at("Road") == 2);
  CHECK(t.area.at("RoofSurface") == Approx(100).epsilon(1e-9));
  CHECK(t.area.at("WallSurface") == Approx(4 * 60).epsilon(1e-9));
  CHECK(t.area.at("Road") == Approx(30 * 3).epsilon(1e-9));
  double max_x = 0;
  for (const auto& v : m.vertices) max_x = std::max(max_x, v.x());
  CHECK(max_x == Approx(100030.0).epsilon(1e-15));
}

TEST_CASE("CityJSON 1.1: Solid, LoD choice, a wall with a window", "[visgraph][cityjson]") {
  // L-shaped house 8 m tall: LoD 2.2 = ground and roof hexagons (4 triangles
  // each) and six walls, one of them with a 3 x 2 m window (8 triangles):
  // 4 + 4 + 8 + 5 x 2 = 26.  LoD 1 = a 10 x 10 m box: 12 triangles.
  const vg::Mesh m = vg::load_cityjson(data("solid_lods_hole_v1.1.city.json"));
  CHECK(m.triangles.size() == 26);
  CHECK(vg::short_crs_name(m.crs) == "EPSG:7415");
  const ClassTally t = tally(m);
  CHECK(t.area.at("RoofSurface") == Approx(64).epsilon(1e-12));
  // Walls: perimeter 40 m x 8 m less the 6 m^2 window.
  CHECK(t.area.at("WallSurface") == Approx(40 * 8 - 6).epsilon(1e-12));
  vg::CityJsonOptions lod1;
  lod1.lod = "1";
  const vg::Mesh box = vg::load_cityjson(data("solid_lods_hole_v1.1.city.json"), lod1);
  CHECK(box.triangles.size() == 12);
  CHECK(box.classes == std::vector<std::string>{"Building"});  // no semantics at LoD 1
  vg::CityJsonOptions lod3;
  lod3.lod = "3";
  CHECK_THAT(load_error(data("solid_lods_hole_v1.1.city.json"), lod3),
             Catch::Contains("solid_lods_hole_v1.1.city.json") && Catch::Contains("no triangles") &&
                 Catch::Contains("LoD 3"));
}

TEST_CASE("CityJSON 2.0: MultiSolid, CompositeSolid, GeometryInstance", "[visgraph][cityjson]") {
  // Two boxes (MultiSolid, 24), one box (CompositeSolid, 12), a template cube
  // [-1,1]^2 x [0,2] scaled by 2 at reference point (50, 50, 0) (12), a
  // TransportSquare quad (2): 50 triangles.
  const vg::Mesh m = vg::load_cityjson(data("solids_template_v2.0.city.json"));
  CHECK(m.triangles.size() == 50);
  const ClassTally t = tally(m);
  CHECK(t.triangles.at("Building") == 24);
  CHECK(t.triangles.at("Bridge") == 12);
  CHECK(t.triangles.at("SolitaryVegetationObject") == 12);
  CHECK(t.triangles.at("TransportSquare") == 2);
  // The instance: x in [48, 52], z in [0, 4].
  Vector3d lo = Vector3d::Constant(1e9), hi = -lo;
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    if (m.classes[m.triangle_class[i]] == "SolitaryVegetationObject")
      for (auto k : m.triangles[i]) lo = lo.cwiseMin(m.vertices[k]), hi = hi.cwiseMax(m.vertices[k]);
  CHECK(lo.isApprox(Vector3d(48, 48, 0)));
  CHECK(hi.isApprox(Vector3d(52, 52, 4)));
}

TEST_CASE("CityJSONSeq: a header line and features with their own vertices", "[visgraph][cityjson]") {
  // LandUse square (2 triangles) and a box building (12); transform 0.5 and
  // (1000, 2000, 0) from the header line.
  const vg::Mesh m = vg::load_cityjson(data("two_features.city.jsonl"));
  CHECK(m.triangles.size() == 14);
  CHECK(m.groups == std::vector<std::string>{"a", "b"});
  double max_x = 0;
  for (const auto& tri : m.triangles)
    for (auto k : tri) max_x = std::max(max_x, m.vertices[k].x());
  CHECK(max_x == 1010.0);
  CHECK(vg::looks_like_cityjson("{\"type\":\"CityJSON\",\"version\":\"2.0\"}"));
  CHECK_FALSE(vg::looks_like_cityjson("v 0 0 0\nf 1 2 3\n"));
}

TEST_CASE("CityJSON: zero-area faces and repeated vertices are counted and skipped", "[visgraph][cityjson]") {
  // Five rings: a square with repeated vertices (2 triangles), two distinct
  // corners, three collinear corners, a square with a collinear corner (2),
  // one corner: 3 skipped.
  vg::CityJsonReport report;
  const vg::Mesh m = vg::load_cityjson(data("degenerate_faces.city.json"), {}, &report);
  CHECK(report.surfaces == 5);
  CHECK(report.degenerate_surfaces == 3);
  CHECK(report.invalid_surfaces == 0);
  CHECK(m.triangles.size() == 4);
}

TEST_CASE("CityJSON: malformed files give an error naming file and place", "[visgraph][cityjson]") {
  CHECK_THAT(load_error(data("bad_syntax.city.json")),
             Catch::Contains("bad_syntax.city.json") && Catch::Contains("line 2") && Catch::Contains("not valid JSON"));
  CHECK_THAT(load_error(data("bad_vertex_index.city.json")),
             Catch::Contains("bad_vertex_index.city.json") && Catch::Contains("CityObjects/g/geometry/0/boundaries/3/0/2") &&
                 Catch::Contains("99") && Catch::Contains("out of range"));
  CHECK_THAT(load_error(data("bad_version.city.json")), Catch::Contains("bad_version.city.json") && Catch::Contains("3.0"));
  CHECK_THAT(load_error(data("missing.city.json")), Catch::Contains("missing.city.json") && Catch::Contains("cannot open"));
}

TEST_CASE("CityJSON: the Delfshaven model (real data, shared/)", "[visgraph][cityjson]") {
  // ../shared/data/cityjson/README.md: 853 LoD2 buildings, MultiSurface with
  // Roof/Wall/GroundSurface semantics, EPSG:28992, repeated and degenerate rings.
  const std::string path = std::string(ATTENUVIS_TEST_DATA_DIR) + "/../../../shared/data/cityjson/rotterdam-delfshaven-3-20.city.json";
  if (!std::filesystem::exists(path)) {
    WARN("skipped: " << path << " is absent");
    return;
  }
  vg::CityJsonReport report;
  const vg::Mesh m = vg::load_cityjson(path, {}, &report);
  CHECK(report.city_objects == 853);
  CHECK(report.objects_read == 853);
  CHECK(m.groups.size() == 853);
  CHECK(vg::short_crs_name(m.crs) == "EPSG:28992");
  CHECK(report.degenerate_surfaces > 0);  // the README's zero-area faces
  const ClassTally t = tally(m);
  CHECK(t.triangles.count("RoofSurface") == 1);
  CHECK(t.triangles.count("GroundSurface") == 1);
  CHECK(t.triangles.count("WallSurface") == 1);
  WARN("Delfshaven: " << m.triangles.size() << " triangles, " << report.surfaces << " surfaces, "
                      << report.degenerate_surfaces << " zero-area, " << report.invalid_surfaces << " invalid");
}
