// What the scene-reader targets share: the input through a file with the
// reader's extension, and a mesh that reads handed on to Embree, then given
// the ground a buildings-only model gets (ground.hpp: base points, the
// Delaunay TIN or the plane) and handed on again.
#pragma once

#include "attenuvis/visgraph/ground.hpp"
#include "attenuvis/visgraph/mesh.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

namespace attenuvis::fuzz {

template <typename Load>
int fuzz_scene_reader(const std::uint8_t* data, std::size_t size, const char* extension, Load&& load) {
  const InputFile file(data, size, extension);
  expect_clean_rejection([&] {
    visgraph::Mesh mesh = load(file.path());
    const visgraph::Scene scene(mesh);
    (void)scene;
    visgraph::add_ground(mesh, {});
    const visgraph::Scene grounded(mesh);
    (void)grounded;
  });
  return 0;
}

}  // namespace attenuvis::fuzz
