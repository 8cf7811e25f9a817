// What the scene-reader targets share: the input through a file with the
// reader's extension, and a mesh that reads handed on to Embree.
#pragma once

#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

namespace attenuvis::fuzz {

template <typename Load>
int fuzz_scene_reader(const std::uint8_t* data, std::size_t size, const char* extension, Load&& load) {
  const InputFile file(data, size, extension);
  expect_clean_rejection([&] {
    const visgraph::Mesh mesh = load(file.path());
    const visgraph::Scene scene(mesh);
    (void)scene;
  });
  return 0;
}

}  // namespace attenuvis::fuzz
