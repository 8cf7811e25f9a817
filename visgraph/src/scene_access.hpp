// The Embree handle behind a Scene, for the library's own kernels only: the
// public header keeps Embree's types out of every other module.
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <embree3/rtcore.h>

namespace attenuvis::visgraph::detail {

struct SceneAccess {
  static RTCScene embree(const Scene& scene);
};

}  // namespace attenuvis::visgraph::detail
