// Wavefront OBJ scenes; a mesh that reads is also handed to Embree and measured.
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/obj.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const fuzz::InputFile file(data, size, ".obj");
  fuzz::expect_clean_rejection([&] {
    const visgraph::Mesh mesh = visgraph::load_obj(file.path());
    const visgraph::Scene scene(mesh);
    (void)scene;
  });
  return 0;
}
