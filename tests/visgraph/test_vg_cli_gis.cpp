// `attenuvis vg` on what GIS users have: footprints with heights (a
// GeoPackage, GeoJSON) standing on a DEM (a GeoTIFF), both written here with
// GDAL.  End to end: prisms on the DEM, nodes on its surface, holes and
// multipolygons respected, features without a height counted; and every
// refusal before any work: a DEM in another CRS, without data where nodes
// stand, not covering the model; footprints in degrees, not polygons, an
// empty layer, a self-intersecting ring, a missing field or height.
#include "cli_test_support.hpp"
#include "gis_files.hpp"

#include <attenuvis/visgraph/gis/utm.hpp>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace clitest;
using namespace vgtest;
using Catch::Matchers::Contains;

namespace {

constexpr int kUtm32N = 32632;
constexpr double kX0 = 500000, kYTop = 5000100;  // the DEM's top-left corner

// The DEM's surface: a plane, so that linear interpolation between cell
// centres is exact and every node's height is known.
double plane(double x, double y) { return 300.0 + 0.1 * (x - kX0) + 0.05 * (y - (kYTop - 100)); }

// f1 a 10 m square (12 m), f2 a 30 m square around a 10 m courtyard (9 m),
// f3 two 8 m squares (3 levels = 9 m), f4 no height at all.
std::vector<TestFeature> town() {
  return {{{{rectangle(kX0 + 20, kYTop - 80, kX0 + 30, kYTop - 70)}}, 12.0, std::nullopt},
          {{{rectangle(kX0 + 50, kYTop - 80, kX0 + 80, kYTop - 50), rectangle(kX0 + 60, kYTop - 70, kX0 + 70, kYTop - 60)}},
           9.0,
           std::nullopt},
          {{{rectangle(kX0 + 20, kYTop - 40, kX0 + 28, kYTop - 32)}, {rectangle(kX0 + 35, kYTop - 40, kX0 + 43, kYTop - 32)}},
           std::nullopt,
           3.0},
          {{{rectangle(kX0 + 90, kYTop - 30, kX0 + 95, kYTop - 25)}}, std::nullopt, std::nullopt}};
}

bool inside(double x, double y, double x0, double y0, double x1, double y1) {
  return x > x0 && x < x1 && y > y0 && y < y1;
}

std::string vg_command(const TempDir& dir, const std::string& footprints, const std::string& dem,
                       const std::string& extra = "") {
  return "vg " + (dir / footprints) + " --height-field height --levels-field levels --terrain " + (dir / dem) +
         " --conditions clear --spacing 2 --out " + (dir / "n.csv") + " " + extra;
}

}  // namespace

TEST_CASE("vg on footprints and a DEM: prisms on the terrain, nodes on its surface", "[visgraph][cli][gis]") {
  TempDir dir;
  write_geotiff(dir / "dem.tif", kUtm32N, kX0, kYTop, 1.0, 120, 100, plane);
  write_footprints(dir / "fp.gpkg", "GPKG", kUtm32N, town());
  const Run r = run(vg_command(dir, "fp.gpkg", "dem.tif", "--summary " + (dir / "s.json")));
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("1 of 4 features have no usable height (height or levels) and were skipped") &&
                           Contains("feature 4: height is empty, levels is empty") &&
                           Contains("ground: a DEM, " + (dir / "dem.tif") + " (EPSG:32632, 1 x 1 m cells") &&
                           Contains("DEMTerrain"));
  const Csv csv = read_csv(dir / "n.csv");
  const std::size_t x = csv.column("x"), y = csv.column("y"), z = csv.column("z");
  std::size_t courtyard = 0;
  for (const auto& row : csv.rows) {
    INFO("node at " << row[x] << ", " << row[y]);
    // On the DEM's surface (single-precision Embree hit: 1 mm).
    CHECK(row[z] - 1.7 == Approx(plane(row[x], row[y])).margin(1e-3));
    // Never inside a building; in the courtyard, yes (the hole is open).
    CHECK_FALSE(inside(row[x], row[y], kX0 + 20, kYTop - 80, kX0 + 30, kYTop - 70));
    const bool in_ring = inside(row[x], row[y], kX0 + 50, kYTop - 80, kX0 + 80, kYTop - 50);
    const bool in_hole = inside(row[x], row[y], kX0 + 60, kYTop - 70, kX0 + 70, kYTop - 60);
    CHECK((!in_ring || in_hole));
    courtyard += in_hole;
    CHECK_FALSE(inside(row[x], row[y], kX0 + 20, kYTop - 40, kX0 + 28, kYTop - 32));
    CHECK_FALSE(inside(row[x], row[y], kX0 + 35, kYTop - 40, kX0 + 43, kYTop - 32));
  }
  CHECK(courtyard == 25);  // 5 x 5 cells of 2 m in the 10 m courtyard
  std::ifstream summary(dir / "s.json");
  const auto s = nlohmann::json::parse(summary);
  CHECK(s["scene"]["crs"] == "EPSG:32632");
  CHECK_THAT(s["scene"]["format"].get<std::string>(), Contains("3 of 4 features extruded"));
  CHECK_THAT(s["scene"]["ground"].get<std::string>(), Contains("a DEM"));

  // The same layer as GeoJSON; --strict refuses the feature without a height.
  write_footprints(dir / "fp.geojson", "GeoJSON", kUtm32N, town());
  const Run strict = run(vg_command(dir, "fp.geojson", "dem.tif", "--strict"));
  CHECK(strict.status != 0);
  CHECK_THAT(strict.output, Contains("fp.geojson: feature 3 has no usable height (height is empty, levels is empty)"));
  CHECK_FALSE(std::filesystem::exists(dir / "n.csv.tmp"));
}

TEST_CASE("vg refuses a DEM in another CRS, without data where nodes stand, or short of the model", "[visgraph][cli][gis]") {
  TempDir dir;
  write_footprints(dir / "fp.gpkg", "GPKG", kUtm32N, town());
  write_geotiff(dir / "dem33.tif", 32633, kX0, kYTop, 1.0, 120, 100, plane);
  Run r = run(vg_command(dir, "fp.gpkg", "dem33.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("dem33.tif is in EPSG:32633 but the model in EPSG:32632"));
  // A cell without data in the open between the buildings: column 45, row
  // 50 (centre x0 + 45.5, y_top - 50.5).
  write_geotiff(dir / "hole.tif", kUtm32N, kX0, kYTop, 1.0, 120, 100, plane, {{45, 50}});
  r = run(vg_command(dir, "fp.gpkg", "hole.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("hole.tif has no data at cell (column 45, row 50) at x = 500045.5, y = 5000049.5") &&
                           Contains("where nodes would stand"));
  CHECK_FALSE(std::filesystem::exists(dir / "n.csv"));
  // Under a building (f1 covers columns 20..29, rows 70..79) it does no harm.
  write_geotiff(dir / "masked.tif", kUtm32N, kX0, kYTop, 1.0, 120, 100, plane, {{24, 74}, {25, 75}});
  r = run(vg_command(dir, "fp.gpkg", "masked.tif"));
  CHECK(r.status == 0);
  // Given nodes: each one is checked, and one over the hole is named.
  std::ofstream(dir / "eyes.csv") << "x,y,z\n500040.5,5000040.5,310\n500045.5,5000049.2,310\n";
  r = run(vg_command(dir, "fp.gpkg", "hole.tif", "--nodes " + (dir / "eyes.csv")));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("hole.tif has no data at cell (column 45, row 50)") &&
                           Contains("under node 2 (x = 500045.5, y = 5000049.2)"));
  // A DEM that stops short of the buildings.
  write_geotiff(dir / "small.tif", kUtm32N, kX0, kYTop, 1.0, 50, 100, plane);
  r = run(vg_command(dir, "fp.gpkg", "small.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("small.tif does not cover the model: its cell centres span x 500000.5 to 500049.5"));
}

TEST_CASE("vg refuses footprints in degrees, of the wrong geometry, empty, self-intersecting or without the field", "[visgraph][cli][gis]") {
  TempDir dir;
  write_geotiff(dir / "dem.tif", kUtm32N, kX0, kYTop, 1.0, 120, 100, plane);
  // Degrees near 9 E, 45 N: UTM zone 32N.
  const std::vector<TestFeature> degrees = {{{{rectangle(9.0, 45.0, 9.0001, 45.0001)}}, 10.0, std::nullopt}};
  write_footprints(dir / "wgs84.gpkg", "GPKG", 4326, degrees);
  Run r = run(vg_command(dir, "wgs84.gpkg", "dem.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("is in EPSG:4326, measured in degrees: a projected CRS in metres is needed, e.g. "
                                "UTM zone 32N (EPSG:32632) for its extent"));
  std::ofstream(dir / "lines.geojson")
      << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},)"
      << R"("features":[{"type":"Feature","properties":{"height":5,"levels":2},)"
      << R"("geometry":{"type":"LineString","coordinates":[[500010,5000010],[500020,5000020]]}}]})";
  r = run(vg_command(dir, "lines.geojson", "dem.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("feature 0 is a Line String: footprints must be polygons or multipolygons"));
  write_footprints(dir / "empty.gpkg", "GPKG", kUtm32N, {});
  r = run(vg_command(dir, "empty.gpkg", "dem.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("layer 'buildings' has no features"));
  // A bow tie: (20,20) (30,30) (30,20) (20,30).
  std::vector<TestFeature> bow = town();
  bow.push_back({{{{{kX0 + 100, kYTop - 20}, {kX0 + 110, kYTop - 10}, {kX0 + 110, kYTop - 20}, {kX0 + 100, kYTop - 10},
                    {kX0 + 100, kYTop - 20}}}},
                 8.0,
                 std::nullopt});
  write_footprints(dir / "bow.gpkg", "GPKG", kUtm32N, bow);
  r = run(vg_command(dir, "bow.gpkg", "dem.tif"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("bow.gpkg: feature 5, outline intersects itself"));
  r = run("vg " + (dir / "bow.gpkg") + " --height-field hoehe --conditions clear --out " + (dir / "n.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("has no field 'hoehe' (the height field); its fields: height, levels"));
  // Without a height field the file is not a scene, and the message says why.
  r = run("vg " + (dir / "bow.gpkg") + " --conditions clear --out " + (dir / "n.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("is a GeoPackage (SQLite) file of GIS features, not a scene") &&
                           Contains("--height-field"));
  CHECK_FALSE(std::filesystem::exists(dir / "n.csv"));
}

TEST_CASE("UTM zones for data in degrees", "[visgraph][gis]") {
  namespace gis = attenuvis::visgraph::gis;
  // Zone = floor((lon + 180) / 6) + 1; EPSG 326zz north, 327zz south (the
  // EPSG registry's WGS 84 / UTM zone codes).
  CHECK(gis::utm_zone(4.47, 51.92) == "UTM zone 31N (EPSG:32631)");   // Rotterdam
  CHECK(gis::utm_zone(151.21, -33.87) == "UTM zone 56S (EPSG:32756)");  // Sydney
  CHECK(gis::utm_zone(-180.0, 10.0) == "UTM zone 1N (EPSG:32601)");
  CHECK(gis::utm_zone(180.0, -10.0) == "UTM zone 60S (EPSG:32760)");
  CHECK(gis::utm_zone(6.0, 0.0) == "UTM zone 32N (EPSG:32632)");  // a zone's western edge belongs to it
}

TEST_CASE("vg on a CityJSON model and a DEM: the horizontal CRS decides, the vertical datum does not", "[visgraph][cli][gis]") {
  // box_on_terrain_v1.0: EPSG:28992 (RD New), x 100000..100030, y 399996..400030.
  TempDir dir;
  const std::string model = std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/cityjson/box_on_terrain_v1.0.city.json";
  const auto flat = [](double, double) { return 0.5; };
  // EPSG:7415 is RD New + NAP height: the same horizontal CRS.
  write_geotiff(dir / "rd_nap.tif", 7415, 99990, 400040, 1.0, 50, 50, flat);
  Run r = run("vg " + model + " --terrain " + (dir / "rd_nap.tif") + " --conditions clear --out " + (dir / "n.csv"));
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Contains("ground: a DEM"));
  write_geotiff(dir / "utm.tif", 32631, 99990, 400040, 1.0, 50, 50, flat);
  r = run("vg " + model + " --terrain " + (dir / "utm.tif") + " --conditions clear --out " + (dir / "m.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("utm.tif is in EPSG:32631 but the model in EPSG:28992"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.csv"));
  // Generated scenes have no place on a DEM.
  r = run("vg layout:1 --terrain " + (dir / "utm.tif") + " --conditions clear --out " + (dir / "m.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("--terrain, --height-field and --levels-field apply to scene files"));
}
