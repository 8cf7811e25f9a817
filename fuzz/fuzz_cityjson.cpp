// CityJSON and CityJSONSeq scenes; a mesh that reads is also handed to Embree.
#include "attenuvis/visgraph/cityjson.hpp"
#include "fuzz_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return attenuvis::fuzz::fuzz_scene_reader(data, size, ".city.json",
                                            [](const std::string& path) { return attenuvis::visgraph::load_cityjson(path); });
}
