// CityJSON and CityJSONSeq scenes; a mesh that reads is also handed to Embree.
#include "attenuvis/visgraph/cityjson.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const fuzz::InputFile file(data, size, ".city.json");
  fuzz::expect_clean_rejection([&] {
    const visgraph::Mesh mesh = visgraph::load_cityjson(file.path());
    const visgraph::Scene scene(mesh);
    (void)scene;
  });
  return 0;
}
