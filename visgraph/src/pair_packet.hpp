// Sixteen pairs from one origin, prepared for rtcOccluded16: the line-of-sight
// policy of visibility.hpp (coincident pairs, the end gap, pairs too close to
// hold geometry) applied to all lanes at once.  Internal to the visgraph
// library; the scoring engine and the raw Embree loop of the benchmarks both
// build their packets here, so their speed ratio measures scoring alone.
#pragma once

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>

namespace attenuvis::visgraph::detail {

constexpr double kCoincident = 1e-6;  // m: pairs closer than this are never cast nor counted

struct PairPacket {
  RTCRay16 ray;
  alignas(64) int valid[kLanes];          // -1: lane is cast
  alignas(64) double distance[kLanes];    // m; 0 unless the pair is a line-of-sight candidate
  alignas(64) double visible[kLanes];     // 1.0 or 0.0 (final after resolve_packet)
  int cast = 0;                           // lanes cast
  int coincident = 0;                     // lanes with d < kCoincident
  int visible_count = 0;                  // lanes with visible = 1 (final after resolve_packet)
};

// Lanes l < n take partners (px[l], py[l], pz[l]) against the origin
// (ox, oy, oz) (local frame); lanes >= n are idle.  A pair farther than
// max_distance is no candidate.  px/py/pz need n readable values.
// Bit-identical on every CPU: no contraction into FMA (see contrast_kernel.cpp).
void build_packet(double ox, double oy, double oz, const double* px, const double* py, const double* pz, int n,
                  double max_distance, PairPacket& packet);

// After rtcOccluded16 on packet.valid/packet.ray: visible = 1 for cast lanes
// whose ray was not occluded (Embree sets tfar = -inf when occluded); also
// updates visible_count.
void resolve_packet(PairPacket& packet);

// Adds one scored packet (c_fixed, d_fixed from contrast_lanes on its
// distance/visible lanes) to the row's lane totals row_lanes[s * 16 + l],
// slots s = degree, distance, one per sigma (the caller sums the lanes at
// the end of the row).  If `acc` is not null, also credits the partners
// j0 + l (l < n) in the slot-major accumulators acc[s * N + j].
void accumulate_packet(const PairPacket& packet, const std::int64_t* c_fixed, const std::int64_t* d_fixed, int K,
                       int n, std::int64_t* row_lanes, std::int64_t* acc, std::size_t N, std::size_t j0);

}  // namespace attenuvis::visgraph::detail
