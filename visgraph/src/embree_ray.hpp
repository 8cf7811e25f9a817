// One ray as Embree's rtcIntersect1 takes it.  Internal to the visgraph
// library: the scene's own queries (scene.cpp) and the culling's probe rays
// (packet_culling.cpp, pair_culling.cpp) build it the same way.
#pragma once

#include <embree3/rtcore.h>

namespace attenuvis::visgraph::detail {

// From o along d, t in [t_near, t_far] in units of |d| (d need not be unit
// length: with t_far = 1 the ray ends at o + d), every geometry (mask all
// ones), no hit yet.  Narrowed to float, the precision Embree intersects in.
inline RTCRayHit embree_ray(const double o[3], const double d[3], double t_near, double t_far) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o[0]);
  rh.ray.org_y = static_cast<float>(o[1]);
  rh.ray.org_z = static_cast<float>(o[2]);
  rh.ray.dir_x = static_cast<float>(d[0]);
  rh.ray.dir_y = static_cast<float>(d[1]);
  rh.ray.dir_z = static_cast<float>(d[2]);
  rh.ray.tnear = static_cast<float>(t_near);
  rh.ray.tfar = static_cast<float>(t_far);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace attenuvis::visgraph::detail
