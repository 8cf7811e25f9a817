// Scene files by content (scene_file.hpp): one scene as z-up OBJ, y-up OBJ,
// glTF and GLB (tests/data/visgraph/gltf/, written together by one script:
// a 40 x 40 m ground and two closed boxes, 10 x 5 and 5 x 15 m, placed at
// (100, 200, 0); the glTF places it by a parent node's translation) gives
// the same nodes and the same scores; the up-axis warning; glTF errors.
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_file.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <string>

namespace vg = attenuvis::visgraph;

namespace {
std::string data(const std::string& name) { return std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/gltf/" + name; }

struct Run {
  vg::NodeSet nodes;
  vg::VisibilityResult result;
};
Run run(const vg::Mesh& mesh) {
  const vg::Scene scene(mesh);
  Run r;
  r.nodes = vg::generate_nodes(scene, vg::NodeGridOptions{});
  vg::VisibilityOptions o;
  o.sigmas = {0.02, 0.2};
  r.result = vg::all_to_all(scene, r.nodes.eyes, o);
  return r;
}
}  // namespace

TEST_CASE("OBJ (z-up, y-up) and glTF (.gltf, .glb) of one scene give the same nodes and scores",
          "[visgraph][scene_files]") {
  const vg::SceneFile obj = vg::load_scene_file(data("scene_z_up.obj"));
  CHECK(obj.format == "OBJ");
  CHECK(obj.warnings.empty());
  const Run reference = run(obj.mesh);
  // 1600 cells less 50 and 75 under the boxes.
  CHECK(reference.nodes.eyes.size() == 1475);
  vg::SceneFileOptions y_up;
  y_up.obj_up_axis = vg::UpAxis::y;
  for (const auto& [name, options] : {std::pair<std::string, vg::SceneFileOptions>{"scene.gltf", {}},
                                      {"scene.glb", {}},
                                      {"scene_y_up.obj", y_up}}) {
    INFO(name);
    const vg::SceneFile file = vg::load_scene_file(data(name), options);
    CHECK(file.warnings.empty());
    CHECK(file.mesh.groups == obj.mesh.groups);
    const Run r = run(file.mesh);
    CHECK(r.nodes.eyes == reference.nodes.eyes);
    CHECK(r.result.degree == reference.result.degree);
    CHECK(r.result.sum == reference.result.sum);  // bit for bit
  }
  CHECK(vg::load_scene_file(data("scene.gltf")).format == "glTF");
}

TEST_CASE("an OBJ exported y-up and read z-up is flagged", "[visgraph][scene_files]") {
  // Read as z-up, the y-up file is 40 m tall and 10 m deep.
  const vg::SceneFile file = vg::load_scene_file(data("scene_y_up.obj"));
  REQUIRE(file.warnings.size() == 1);
  CHECK_THAT(file.warnings[0], Catch::Contains("--up-axis y"));
  CHECK_THROWS_WITH(vg::parse_up_axis("x"), Catch::Contains("'x'"));
}

TEST_CASE("glTF errors name the file and what is wrong", "[visgraph][scene_files]") {
  try {
    vg::load_scene_file(data("bad_accessor.gltf"));
    FAIL("no error");
  } catch (const std::exception& e) {
    // tinygltf checks accessors itself; its message comes through with the file.
    CHECK_THAT(e.what(), Catch::Contains("bad_accessor.gltf") && Catch::Contains("accessor"));
  }
  vg::SceneFileOptions lod;
  lod.lod = "2";
  CHECK_THROWS_WITH(vg::load_scene_file(data("scene.gltf"), lod), Catch::Contains("--lod"));
}
