// glTF 2.0 scenes, text (.gltf) or binary (.glb, chosen by the "glTF" magic as
// load_scene_file does); a mesh that reads is also handed to Embree.
#include "attenuvis/visgraph/detail/gltf.hpp"
#include "fuzz_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return attenuvis::fuzz::fuzz_scene_reader(data, size, ".gltf",
                                            [](const std::string& path) { return attenuvis::visgraph::load_gltf(path); });
}
