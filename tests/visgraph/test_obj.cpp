// OBJ reading and writing (visgraph/src/obj.cpp): exact round trip of
// UTM-sized coordinates, triangulation, group and material names, and one
// clear error (file and line) per kind of bad input.
#include <catch2/catch.hpp>

#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/obj.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>

namespace fs = std::filesystem;
using attenuvis::visgraph::load_obj;
using attenuvis::visgraph::Mesh;
using attenuvis::visgraph::walkable_area;
using attenuvis::visgraph::write_obj;

namespace {

std::string data(const std::string& name) { return std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/" + name; }

// A fresh empty directory under the system temp dir, removed at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("attenuvis-mesh-io-" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// Message of the std::runtime_error `load_obj(path)` throws ("" if none).
std::string load_error(const std::string& path) {
  try {
    load_obj(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string group_of(const Mesh& m, std::size_t t) { return m.groups[m.triangle_group[t]]; }

}  // namespace

TEST_CASE("OBJ round trip keeps UTM-sized coordinates bit for bit", "[visgraph][mesh_io]") {
  // Coordinates as a UTM zone gives them: easting ~5e5 m, northing ~5e6 m,
  // with more digits than a float (or a digit-summing parser) keeps.
  Mesh mesh;
  std::mt19937_64 engine(7);
  const auto unit = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  for (int i = 0; i < 200; ++i)
    mesh.vertices.emplace_back(500000.0 + 1000.0 * unit(), 5400000.0 + 1000.0 * unit(), 30.0 * unit() - 5.0);
  mesh.vertices.emplace_back(512345.67890123456, 5412345.6789012345, 0.1);  // 17 significant digits
  const std::vector<std::string> names{"sidewalk", "crosswalk", "building"};
  for (const auto& n : names) mesh.add_group(n);
  // Triangles already sorted by group, as write_obj orders them.
  for (std::uint32_t g = 0; g < 3; ++g)
    for (std::uint32_t k = 0; k < 20; ++k) {
      const std::uint32_t a = (67 * (20 * g + k)) % 201;
      mesh.triangles.push_back({a, (a + 1) % 201, (a + 2) % 201});
      mesh.triangle_group.push_back(g);
    }

  TempDir dir;
  const std::string path = (dir.path / "utm.obj").string();
  write_obj(mesh, path);
  const Mesh back = load_obj(path);

  REQUIRE(back.vertices.size() == mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    INFO("vertex " << i);
    CHECK(back.vertices[i].x() == mesh.vertices[i].x());  // exact: no tolerance
    CHECK(back.vertices[i].y() == mesh.vertices[i].y());
    CHECK(back.vertices[i].z() == mesh.vertices[i].z());
  }
  CHECK(back.triangles == mesh.triangles);
  REQUIRE(back.triangle_group.size() == mesh.triangle_group.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) CHECK(group_of(back, t) == group_of(mesh, t));
  // Nothing but the file itself is left in the directory (no temporary).
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator{}) == 1);
}

TEST_CASE("OBJ round trip of interleaved groups keeps every triangle and its group", "[visgraph][mesh_io]") {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto a = static_cast<std::uint32_t>(mesh.add_group("a b"));  // a name with a space
  const auto b = static_cast<std::uint32_t>(mesh.add_group("road"));
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 2, 3}};
  mesh.triangle_group = {a, b, a};
  TempDir dir;
  const std::string path = (dir.path / "groups.obj").string();
  write_obj(mesh, path);
  const Mesh back = load_obj(path);
  using Row = std::tuple<std::string, std::array<std::uint32_t, 3>>;
  std::vector<Row> expected, got;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) expected.emplace_back(group_of(mesh, t), mesh.triangles[t]);
  for (std::size_t t = 0; t < back.triangles.size(); ++t) got.emplace_back(group_of(back, t), back.triangles[t]);
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  CHECK(got == expected);
}

TEST_CASE("OBJ polygons are triangulated and groups kept", "[visgraph][mesh_io]") {
  const Mesh mesh = load_obj(data("polygons_groups.obj"));
  // quad -> 2, pentagon -> 3, triangle -> 1 (fixture header).
  CHECK(mesh.triangles.size() == 6);
  CHECK(mesh.groups == std::vector<std::string>{"sidewalk", "crosswalk"});
  // Triangulation covers each polygon exactly: projected areas from the
  // fixture's coordinates (square 1 + triangle 0.5; pentagon 1 + 0.5).
  CHECK(walkable_area(mesh, {"sidewalk"}) == Approx(1.5).epsilon(1e-12));
  CHECK(walkable_area(mesh, {"crosswalk"}) == Approx(1.5).epsilon(1e-12));
  CHECK(walkable_area(mesh, {"sidewalk", "crosswalk"}) == Approx(3.0).epsilon(1e-12));
  const auto stats = attenuvis::visgraph::mesh_stats(mesh);
  CHECK(stats.lower == Eigen::Vector3d(0, 0, 0));
  CHECK(stats.upper == Eigen::Vector3d(3, 2, 0));
}

TEST_CASE("OBJ without groups names triangles by material, else 'default'", "[visgraph][mesh_io]") {
  // No mtllib in the file: the names must survive anyway.
  const Mesh mesh = load_obj(data("materials_only.obj"));
  REQUIRE(mesh.triangles.size() == 3);
  std::vector<std::string> names;
  for (std::size_t t = 0; t < 3; ++t) names.push_back(group_of(mesh, t));
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"asphalt", "default", "paving"});
}

TEST_CASE("OBJ with CRLF endings, objects and v/vt/vn faces", "[visgraph][mesh_io]") {
  // Fixture: `o curb` (1 triangle), `o kerb stone` + usemtl granite (1), then
  // an unnamed `g ` (1), which falls back to the material still in force.
  // (A bare `g` with no blank after it is ignored by tinyobjloader.)
  const Mesh mesh = load_obj(data("crlf_objects.obj"));
  REQUIRE(mesh.triangles.size() == 3);
  CHECK(group_of(mesh, 0) == "curb");
  CHECK(group_of(mesh, 1) == "kerb stone");
  CHECK(group_of(mesh, 2) == "granite");
  CHECK(mesh.vertices.size() == 4);
  CHECK(mesh.vertices[3] == Eigen::Vector3d(0, 1, 0));
  CHECK(mesh.triangles[2] == std::array<std::uint32_t, 3>{3, 2, 1});
}

TEST_CASE("Bad OBJ input gives an error naming the file and the line", "[visgraph][mesh_io]") {
  SECTION("missing file") {
    const std::string path = data("no_such_file.obj");
    const std::string msg = load_error(path);
    CHECK_THAT(msg, Catch::Contains(path) && Catch::Contains("cannot open"));
  }
  SECTION("a directory") { CHECK_THAT(load_error(data("")), Catch::Contains("directory")); }
  SECTION("NaN vertex") {
    CHECK_THAT(load_error(data("bad_nan_vertex.obj")), Catch::Contains("bad_nan_vertex.obj:5:") &&
                                                           Catch::Contains("not finite"));
  }
  SECTION("overflowing (inf) vertex") {
    CHECK_THAT(load_error(data("bad_inf_vertex.obj")), Catch::Contains("bad_inf_vertex.obj:2:") &&
                                                           Catch::Contains("not finite"));
  }
  SECTION("vertex with two coordinates") {
    CHECK_THAT(load_error(data("bad_short_vertex.obj")), Catch::Contains("bad_short_vertex.obj:2:"));
  }
  SECTION("face index past the last vertex") {
    CHECK_THAT(load_error(data("bad_index.obj")),
               Catch::Contains("bad_index.obj:7:") && Catch::Contains("out of range"));
  }
  SECTION("face index 0") {
    CHECK_THAT(load_error(data("bad_zero_index.obj")), Catch::Contains("bad_zero_index.obj:4:"));
  }
  SECTION("relative index before the first vertex") {
    CHECK_THAT(load_error(data("bad_relative_index.obj")), Catch::Contains("bad_relative_index.obj:4:"));
  }
  SECTION("face with two vertices") {
    CHECK_THAT(load_error(data("bad_short_face.obj")), Catch::Contains("bad_short_face.obj:3:"));
  }
  SECTION("empty mesh") {
    CHECK_THAT(load_error(data("empty_mesh.obj")), Catch::Contains("empty_mesh.obj") && Catch::Contains("empty mesh"));
  }
}

TEST_CASE("write_obj refuses bad meshes and leaves no partial file", "[visgraph][mesh_io]") {
  TempDir dir;
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.add_group("floor");
  mesh.triangles = {{0, 1, 3}};  // index 3 out of range
  mesh.triangle_group = {0};
  const std::string path = (dir.path / "out.obj").string();
  CHECK_THROWS_AS(write_obj(mesh, path), std::runtime_error);
  mesh.triangles = {{0, 1, 2}};
  mesh.vertices[1].x() = std::nan("");
  CHECK_THROWS_AS(write_obj(mesh, path), std::runtime_error);
  CHECK(fs::is_empty(dir.path));
  // Unwritable place: a directory that does not exist.
  mesh.vertices[1].x() = 1.0;
  const std::string nowhere = (dir.path / "missing" / "out.obj").string();
  try {
    write_obj(mesh, nowhere);
    FAIL("write_obj into a missing directory did not throw");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains(nowhere));
  }
  CHECK(fs::is_empty(dir.path));
}
