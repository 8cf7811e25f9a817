// Packets decided lane by lane (packet_culling.hpp).
#include "packet_culling.hpp"

#include "embree_ray.hpp"

#include <algorithm>
#include <cmath>

namespace attenuvis::visgraph::detail {

namespace {
// Rays cast along open lanes to find occluders, per packet: each costs a
// good part of what casting the packet does.
constexpr int kRays = 2;
// Surfaces tried along one such ray (as PairCulling::kOccluderTries).
constexpr int kSurfaces = 4;

// Puts t first among the hints (the others keep their order).
void remember(PacketCulling::Hints& hints, std::uint32_t t) {
  // Shifted element by element: std::copy_backward becomes a call of
  // memmove, which cost more than the rest of the packet's bookkeeping.
  std::uint32_t* h = hints.triangle;
  int at = 0;
  while (at < PacketCulling::kHints - 1 && h[at] != t) ++at;
  for (; at > 0; --at) h[at] = h[at - 1];
  h[0] = t;
}
}  // namespace

std::uint32_t PacketCulling::unblocked(std::uint32_t t, const PacketLines& p, std::uint32_t open,
                                       TriedSolids& tried) const {
  const std::int32_t solid = geometry_->solid_of(t);
  bool with_solid = solid >= 0 && std::find(tried.solid, tried.solid + tried.count, solid) == tried.solid + tried.count;
  if (with_solid && tried.count < 16) tried.solid[tried.count++] = solid;
  return open & ~geometry_->lanes_blocked(t, p, margin_, with_solid);
}

Verdict PacketCulling::decide(const double* point, const double* x, const double* y, const double* z, int n,
                              Hints& hints, Hints& near, EyePlane::Fan& fan, std::size_t row, bool occluders) const {
  if (!geometry_ || n <= 0 || (!plane_ && !occluders)) return Verdict::cast;
  const std::uint32_t all = (1u << n) - 1u;
  std::uint32_t open = all;
  if (plane_ && plane_->holds(point[2])) {
    if (fan.eye != row) {
      plane_->fill(point[0], point[1], fan);
      fan.eye = row;
    }
    open &= ~plane_->lanes_blocked(fan, point, x, y, z, n);
    if (!open) return Verdict::blocked;
  }
  if (!occluders) return Verdict::cast;
  PacketLines p;
  set_lines(p, point, x, y, z, n);
  TriedSolids tried;
  for (const Hints* list : {&hints, &near})
    for (int h = 0; h < kHints && open; ++h) {
      const std::uint32_t t = list->triangle[h];
      if (t == kNoHint) break;
      open = unblocked(t, p, open, tried);
    }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int ray = 0; ray < kRays && open; ++ray) {
    const int l = __builtin_ctz(open);
    const double d[3] = {x[l] - point[0], y[l] - point[1], z[l] - point[2]};
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(length > 4 * margin_)) return Verdict::cast;
    RTCRayHit rh = embree_ray(point, d, 0.0, 1.0);
    rtcIntersect1(scene_, &context, &rh);
    // Nothing along lane l: it is in sight or near an edge, and either way
    // a ray decides it (see packet_culling.hpp).
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Verdict::cast;
    for (int surface = 0; surface < kSurfaces; ++surface) {
      const std::uint32_t left = unblocked(rh.hit.primID, p, open, tried);
      if (left != open) {
        remember(hints, rh.hit.primID);
        remember(near, rh.hit.primID);
      }
      open = left;
      if (!(open >> l & 1u)) break;
      rh.ray.tnear = rh.ray.tfar + static_cast<float>(margin_ / length);
      rh.ray.tfar = 1.0f;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      if (!(rh.ray.tnear < 1.0f)) break;
      rtcIntersect1(scene_, &context, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    }
    if (open >> l & 1u) return Verdict::cast;  // the surfaces along lane l do not certify it
  }
  return open ? Verdict::cast : Verdict::blocked;
}

}  // namespace attenuvis::visgraph::detail
