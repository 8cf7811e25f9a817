// glTF 2.0 scenes, text (.gltf) or binary (.glb, chosen by the "glTF" magic as
// load_scene_file does); a mesh that reads is also handed to Embree.
#include "attenuvis/visgraph/gltf.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const fuzz::InputFile file(data, size, ".gltf");
  fuzz::expect_clean_rejection([&] {
    const visgraph::Mesh mesh = visgraph::load_gltf(file.path());
    const visgraph::Scene scene(mesh);
    (void)scene;
  });
  return 0;
}
