// Wavefront OBJ scenes; a mesh that reads is also handed to Embree.
#include "attenuvis/visgraph/obj.hpp"
#include "fuzz_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return attenuvis::fuzz::fuzz_scene_reader(data, size, ".obj",
                                            [](const std::string& path) { return attenuvis::visgraph::load_obj(path); });
}
