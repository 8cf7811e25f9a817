// Hostile input to the visibility graph's library: coordinates outside the
// documented range (limits.hpp), fixed-point sums that could overflow,
// grid spacings and eye heights that would overflow the grid or Embree's
// ray bounds, over-long OBJ faces and files that are not regular files.
// Each ends in a clean error that names the value and the range, or in the
// right answer.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/city.hpp>
#include <attenuvis/visgraph/geojson.hpp>
#include <attenuvis/visgraph/detail/gltf.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/obj.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_file.hpp>
#include <attenuvis/visgraph/visibility.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace vg = attenuvis::visgraph;
using namespace vgtest;
using Catch::Matchers::Contains;

namespace {
// A small floor far below the sight lines: the scene only has to exist.
vg::Scene small_scene() {
  static const Mesh m = [] {
    Mesh mesh;
    add_floor(mesh, -1, 1, -1, 1, -100, "floor");
    return mesh;
  }();
  return vg::Scene(m);
}

vg::VisibilityOptions sigma_zero() {
  vg::VisibilityOptions o;
  o.sigmas = {0.0};
  o.distance_stats = true;
  o.threads = 1;
  return o;
}

struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name, const std::string& text)
      : path("/tmp/attenuvis-limits-" + std::to_string(::getpid()) + "-" + name) {
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("nodes 1e200 m apart are refused, not summed into a wrapped integer", "[visgraph][limits]") {
  const vg::Scene scene = small_scene();
  // Was: signed overflow of the distance sum (UBSan), S_S = -4405248 in Release.
  const std::vector<Eigen::Vector3d> far = {{0, 0, 0}, {1e200, 0, 0}};
  const std::string msg = error_of([&] { vg::all_to_all(scene, far, sigma_zero()); });
  CHECK_THAT(msg, Contains("node 2") && Contains("1e+200") && Contains("[-1e7, 1e7]"));
}

TEST_CASE("nodes at the edge of the coordinate range give the exact answer", "[visgraph][limits]") {
  const vg::Scene scene = small_scene();
  // 2e7 m apart (past 2^24 m, where a float loses the metre): sigma = 0 makes
  // C = 1 exactly, and 2e7 m is a whole number of 2^-20 m units.
  const std::vector<Eigen::Vector3d> ends = {{-1e7, 0, 0}, {1e7, 0, 0}};
  const vg::VisibilityResult r = vg::all_to_all(scene, ends, sigma_zero());
  REQUIRE(r.degree == std::vector<std::uint32_t>{1, 1});
  CHECK(r.sum[0][0] == 1.0);
  CHECK(r.sum[0][1] == 1.0);
  CHECK(r.mean_distance[0] == 2e7);
  CHECK(r.max_distance[1] == 2e7);
}

TEST_CASE("distance sums that could pass 2^63 are refused before the pass", "[visgraph][limits]") {
  const vg::Scene scene = small_scene();
  // 320,000 targets at (1e7, +-1e7, 0), the source at (-1e7, 0, 0): the
  // points' bounding-box diagonal is 2e7 sqrt(2) = 2.83e7 m, and
  // 320,000 x 2.83e7 m x 2^20 = 9.5e18 > 2^63 = 9.22e18.
  std::vector<Eigen::Vector3d> targets;
  for (int k = 0; k < 320000; ++k) targets.emplace_back(1e7, k % 2 ? 1e7 : -1e7, 0);
  const std::vector<Eigen::Vector3d> source = {{-1e7, 0, 0}};
  const std::string msg = error_of([&] { vg::to_targets(scene, source, targets, sigma_zero()); });
  CHECK_THAT(msg, Contains("overflow the 64-bit distance sums"));
  // The same run limited to 1 km: the bound holds and the pass runs (no target within reach).
  vg::VisibilityOptions near = sigma_zero();
  near.max_distance = 1000;
  const vg::VisibilityResult r = vg::to_targets(scene, source, targets, near);
  CHECK(r.pairs_visible == 0);
}

TEST_CASE("a scene vertex outside the coordinate range is refused", "[visgraph][limits]") {
  Mesh m;
  add_floor(m, 0, 1, 0, 1, 0, "floor");
  m.vertices[0].x() = 3e7;
  CHECK_THAT(error_of([&] { vg::Scene s(m); }), Contains("vertex 1") && Contains("3e+07") && Contains("[-1e7, 1e7]"));
}

TEST_CASE("grid spacing and eye height outside their ranges are refused", "[visgraph][limits]") {
  const vg::Scene scene = small_scene();
  vg::NodeGridOptions o;
  o.spacing = 1e300;  // was: Embree's ray.valid() assertion (SIGABRT)
  CHECK_THAT(error_of([&] { vg::generate_nodes(scene, o); }), Contains("spacing") && Contains("[0.001, 10000]"));
  o.spacing = 1e-300;  // was: one node, silently (extent / spacing = inf)
  CHECK_THAT(error_of([&] { vg::generate_nodes(scene, o); }), Contains("spacing") && Contains("1e-300"));
  o.spacing = 1;
  o.eye_height = 1e300;  // was: the same assertion
  CHECK_THAT(error_of([&] { vg::generate_nodes(scene, o); }), Contains("eye height") && Contains("[0, 1000]"));
}

TEST_CASE("a grid of more cells than the limit is refused with its size", "[visgraph][limits]") {
  Mesh m;
  add_floor(m, 0, 50, 0, 50, 0, "floor");
  const vg::Scene scene(m);
  vg::NodeGridOptions o;
  o.spacing = 1e-3;  // 5e4 x 5e4 = 2.5e9 cells (was: 2 GB in 20 s and growing)
  CHECK(vg::estimate_grid(scene, o.spacing).cells == 2.5e9);
  CHECK_THAT(error_of([&] { vg::generate_nodes(scene, o); }), Contains("2.5e+09 cells") && Contains("larger spacing"));
}

TEST_CASE("the work estimate counts the pairs the pass will consider", "[visgraph][limits]") {
  // 100 nodes 1 m apart on a line: all pairs 4950; within 2.5 m each node has
  // 2 partners after it, the last two 1 and 0: 98 x 2 + 1 = 197.
  std::vector<Eigen::Vector3d> line;
  for (int k = 0; k < 100; ++k) line.emplace_back(k, 0, 0);
  vg::VisibilityOptions o = sigma_zero();
  CHECK(vg::estimate_work(line, nullptr, o).pairs == 4950);
  o.max_distance = 2.5;
  CHECK(vg::estimate_work(line, nullptr, o).pairs == 197);
  // To targets: each of the 100 sources against the targets within 2.5 m in x.
  const std::vector<Eigen::Vector3d> target = {{50, 0, 0}};
  CHECK(vg::estimate_work(line, &target, o).pairs == 5);
}

TEST_CASE("readers refuse coordinates outside the range, naming file and line", "[visgraph][limits]") {
  const TempFile obj("far.obj", "v 0 0 0\nv 1 0 0\nv 0 2e7 0\nf 1 2 3\n");
  CHECK_THAT(error_of([&] { vg::load_obj(obj.path); }), Contains(obj.path + ":3") && Contains("[-1e7, 1e7]"));
  const TempFile csv("far.csv", "x,y,z\n1,2,3\n1,-1.5e7,3\n");
  CHECK_THAT(error_of([&] { vg::read_nodes_csv(csv.path); }), Contains(csv.path + ":3") && Contains("-1.5e+07"));
  const TempFile geo("far.geojson", R"({"type":"Point","coordinates":[1e8,0,0]})");
  CHECK_THAT(error_of([&] { vg::read_nodes(geo.path); }), Contains(geo.path) && Contains("1e+08"));
  CHECK_THAT(error_of([&] { vg::parse_point("0,0,1e300"); }), Contains("[-1e7, 1e7]"));
  // UTM-sized coordinates (zone 31U, a northing of 5.7e6 m) are read.
  const TempFile utm("utm.csv", "500000.25,5700000.5,12\n");
  CHECK(vg::read_nodes_csv(utm.path).front() == Eigen::Vector3d(500000.25, 5700000.5, 12));
}

TEST_CASE("an OBJ face of 100,000 vertices is refused at once with its line", "[visgraph][limits]") {
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a face that would take ~40 s to triangulate\nf";
  for (int k = 0; k < 100000; ++k) text += " " + std::to_string(1 + k % 3);
  text += "\n";
  const TempFile obj("long_face.obj", text);
  CHECK_THAT(error_of([&] { vg::load_obj(obj.path); }), Contains(obj.path + ":5") && Contains("more than 10000"));
}

TEST_CASE("devices are no scene or node files", "[visgraph][limits]") {
  // Were: read for ever, memory growing at 0.5 GB/s.
  for (const std::string device : {"/dev/zero", "/dev/urandom"}) {
    CHECK_THAT(error_of([&] { vg::load_scene_file(device, {}); }), Contains(device) && Contains("not a regular file"));
    CHECK_THAT(error_of([&] { vg::read_nodes(device); }), Contains(device) && Contains("not a regular file"));
    CHECK_THAT(error_of([&] { vg::read_nodes_csv(device); }), Contains("not a regular file"));
  }
}

TEST_CASE("a glTF buffer uri naming a FIFO is refused, not waited on", "[visgraph][limits]") {
  const std::string dir = "/tmp/attenuvis-limits-gltf-" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  REQUIRE(::mkfifo((dir + "/pipe.bin").c_str(), 0600) == 0);
  {
    std::ofstream(dir + "/scene.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"pipe.bin","byteLength":36}],)"
        << R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  }
  // Was: tinygltf's FileExists and ReadWholeFile open the FIFO and block for ever.
  const std::string msg = error_of([&] { vg::load_gltf(dir + "/scene.gltf"); });
  std::filesystem::remove_all(dir);
  CHECK_THAT(msg, Contains("pipe.bin") && Contains("not a regular file"));
}

TEST_CASE("city options outside their ranges are refused with the value", "[visgraph][limits]") {
  vg::CityOptions o;
  o.hex_size = 1e300;  // would have asked for terabytes of street segments
  CHECK_THAT(error_of([&] { vg::make_city(o); }), Contains("hex_size must be in (0, 1000] m, got 1e+300"));
  o = {};
  o.relief = 1e9;  // terrain far outside the coordinate range
  CHECK_THAT(error_of([&] { vg::make_city(o); }), Contains("relief must be in [0, 1000] m"));
}

TEST_CASE("a GeoJSON number beyond any JSON number type is a clean error", "[visgraph][limits]") {
  // Found by fuzz_geojson_nodes: nlohmann throws out_of_range (not a parse
  // error) for 333330000E000000016923..., which escaped the reader.
  const TempFile geo("overflow.geojson", R"({"type":"Point","coordinates":[1,2,333330000E00000001692314756788421404]})");
  CHECK_THAT(error_of([&] { vg::read_nodes(geo.path); }), Contains(geo.path) && Contains("number overflow"));
  CHECK_THROWS_AS(vg::read_geojson_points(geo.path), std::runtime_error);
}

TEST_CASE("no limit lifts the machine's memory: a grid that cannot fit is refused", "[visgraph][limits]") {
  Mesh m;
  add_floor(m, 0, 1e6, 0, 1e6, 0, "floor");
  const vg::Scene scene(m);
  vg::NodeGridOptions o;
  o.spacing = 1e-3;  // 1e18 cells, ~1e20 bytes: more than any machine
  o.max_cells = 0;   // no cell limit (vg --allow-large)
  // Was: a terabyte allocation, std::bad_alloc in Release and an abort under ASan.
  CHECK_THAT(error_of([&] { vg::generate_nodes(scene, o); }), Contains("1e+18 cells") && Contains("machine's"));
}
