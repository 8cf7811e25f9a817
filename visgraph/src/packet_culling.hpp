// Packets of a pair of leaf clusters that PairCulling left to rays, decided
// one by one where possible.  Internal to the visgraph library
// (culled_pass.cpp).
//
// A packet is one row (a node) against up to 16 partners in one leaf.  It
// is blocked when each of its sight lines is blocked by some occluder of
// CullGeometry (a planar triangle or quad, a closed convex solid), each
// with the margins of pair_culling.hpp, now for a single segment: both ends
// at least m from the occluder's plane (or outside the solid), the crossing
// at least m inside it.  Different lanes may be blocked by different
// occluders, which is what a wide pair of clusters cannot use: real
// buildings are many small walls.  On flat ground the row's fan in the
// eyes' plane (eye_plane.hpp) is tried first.  The occluders tried are
// those that blocked the last packets of the same pair of leaves (hints),
// then the surfaces met by a ray along an unblocked lane.  Anything else is cast
// whole, as the same canonical packet as without culling, so every pair
// gets the answer its own ray gives.  A packet is not tested for being all
// in sight: a lane whose ray meets nothing is cast with the rest.  Proving
// such a packet in sight (the hull from its row to the partners' box empty,
// or each lane clear of the triangles near the pair of leaves) took longer
// than Embree takes to cast it (packets in sight near geometry are its
// cheapest), and dropping the hull test made Delfshaven's runs 5 to 10 %
// faster (docs/guide/visgraph-engine.md).
#pragma once

#include "cull_geometry.hpp"
#include "eye_plane.hpp"
#include "pair_culling.hpp"

#include <embree3/rtcore.h>

#include <cstdint>

namespace attenuvis::visgraph::detail {

class PacketCulling {
 public:
  static constexpr int kHints = 4;
  static constexpr std::uint32_t kNoHint = 0xFFFFFFFFu;
  // Triangles whose occluders blocked lanes of the last packets of one
  // pair of leaves, the latest first.
  struct Hints {
    std::uint32_t triangle[kHints] = {kNoHint, kNoHint, kNoHint, kNoHint};
  };

  // Null geometry: every packet is cast.  `plane`: the eyes' plane, where
  // the nodes stand at one height (or null).
  PacketCulling(RTCScene scene, const CullGeometry* geometry, double margin, const EyePlane* plane = nullptr)
      : scene_(scene), geometry_(geometry), margin_(margin), plane_(plane) {}
  bool active() const { return geometry_ != nullptr; }

  // Row `point` against partners (x[l], y[l], z[l]), l < n <= 16 (local
  // frame).  The row's fan in the eyes' plane is tried first (`fan`, filled
  // for `row` when it holds another row's); then, with `occluders`, the
  // occluders: `hints` of this pair of leaves, `near` of the row's leaf (the
  // walls around its rows, whatever the partners), and surfaces found by
  // rays.  `near` carries over between pairs of leaves, so with pass shares
  // (each its own pairs of clusters) the count of packets decided here may
  // differ from one process's; each decision is exact, so no result does.
  // Verdict::blocked or Verdict::cast.
  Verdict decide(const double* point, const double* x, const double* y, const double* z, int n, Hints& hints,
                 Hints& near, EyePlane::Fan& fan, std::size_t row, bool occluders) const;

 private:
  // Clears the bits of the lanes in `open` that triangle t's occluders block.
  // A triangle's solid is tried once per packet: the open lanes only
  // shrink, so a second try on them cannot block more.  `tried` holds the
  // solids tried so far.
  struct TriedSolids {
    std::int32_t solid[16];
    int count = 0;
  };
  std::uint32_t unblocked(std::uint32_t t, const PacketLines& p, std::uint32_t open, TriedSolids& tried) const;

  RTCScene scene_;
  const CullGeometry* geometry_;
  double margin_;
  const EyePlane* plane_;
};

}  // namespace attenuvis::visgraph::detail
