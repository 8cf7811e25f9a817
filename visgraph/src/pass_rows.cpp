// One row's packets and accumulators (pass_rows.hpp).
#include "pass_rows.hpp"

#include "pair_packet.hpp"

#include <attenuvis/visgraph/detail/contrast_kernel.hpp>

#include <algorithm>

namespace attenuvis::visgraph::detail {

namespace {
// Partner coordinates of a packet: contiguous rows j0.. (no copy), or the
// candidates gathered into g*.
struct PacketPartners {
  alignas(64) double gx[kLanes], gy[kLanes], gz[kLanes];
  std::uint32_t index[kLanes];
  const double *x, *y, *z;
  PacketPartners(const Points& P, const std::uint32_t* cand, std::size_t j0, int n) {
    if (cand) {
      for (int l = 0; l < n; ++l) {
        const std::uint32_t j = cand[l];
        index[l] = j;
        gx[l] = P.x[j];
        gy[l] = P.y[j];
        gz[l] = P.z[j];
      }
      x = gx, y = gy, z = gz;
    } else {
      for (int l = 0; l < n; ++l) index[l] = static_cast<std::uint32_t>(j0 + l);
      x = P.x.data() + j0, y = P.y.data() + j0, z = P.z.data() + j0;
    }
  }
};

void cast_packet(const Pass& pass, PairPacket& packet, ThreadState& ts) {
  ts.cast += static_cast<std::uint64_t>(packet.cast);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded16(packet.valid, pass.rtc, &context, &packet.ray);
}
}  // namespace

void add_packet(const Pass& pass, std::size_t i, const std::uint32_t* cand, std::size_t j0, int n,
                std::int64_t* row_lanes, ThreadState& ts, std::vector<Edge>* edges, bool cast_rays) {
  const Points& S = *pass.sources;
  const int K = pass.K;
  const std::size_t N = pass.N;
  PhaseClock clock(pass.time_phases);
  PairPacket packet;
  alignas(64) std::int64_t d_fixed[kLanes];
  std::int64_t* c = ts.c_fixed.data();
  std::int64_t* credit = pass.symmetric && !cand ? ts.acc.data() : nullptr;
  const bool scatter = pass.symmetric && cand;
  const PacketPartners partners(*pass.partners, cand, j0, n);
  build_packet(S.x[i], S.y[i], S.z[i], partners.x, partners.y, partners.z, n, pass.max_distance, packet);
  ts.coincident += static_cast<std::uint64_t>(packet.coincident);
  if (packet.cast) {
    if (cast_rays) {
      ts.seconds.score += clock.lap();
      cast_packet(pass, packet, ts);
      ts.seconds.rays += clock.lap();
    }
    resolve_packet(packet);  // not cast: tfar = 1 - t_near >= 0, every lane in sight
  }
  // A packet with nothing visible adds nothing: skip its scoring (most
  // packets of an occluded scene such as the city).
  if (packet.visible_count == 0) {
    ts.seconds.score += clock.lap();
    return;
  }
  contrast_lanes(packet.distance, packet.visible, pass.neg_sigma.data(), K, c, d_fixed);
  accumulate_packet(packet, c, d_fixed, K, n, row_lanes, credit, N, j0);
  if (scatter || pass.keep_max || edges) {
    for (int l = 0; l < n; ++l) {
      if (packet.visible[l] == 0) continue;
      const std::uint32_t j = partners.index[l];
      const double d = packet.distance[l];
      if (scatter) {
        ts.acc[j] += 1;
        ts.acc[N + j] += d_fixed[l];
        for (int k = 0; k < K; ++k) ts.acc[static_cast<std::size_t>(2 + k) * N + j] += c[k * kLanes + l];
      }
      if (pass.keep_max) {
        ts.max_distance[i] = std::max(ts.max_distance[i], d);
        if (pass.symmetric) ts.max_distance[j] = std::max(ts.max_distance[j], d);
      }
      if (edges) edges->push_back(edge(pass, i, j, d));
    }
  }
  ts.seconds.score += clock.lap();
}

void end_row(const Pass& pass, std::size_t i, const std::int64_t* row_lanes, ThreadState& ts) {
  for (int s = 0; s < 2 + pass.K; ++s) {
    std::int64_t total = 0;
    for (int l = 0; l < kLanes; ++l) total += row_lanes[s * kLanes + l];
    ts.acc[static_cast<std::size_t>(s) * pass.N + i] += total;
    if (s == 0) ts.visible += static_cast<std::uint64_t>(total);
  }
}

void process_row(const Pass& pass, std::size_t i, const std::uint32_t* cand, std::size_t j0, std::size_t count,
                 ThreadState& ts, std::vector<Edge>* edges) {
  std::fill(ts.row.begin(), ts.row.end(), 0);
  for (std::size_t start = 0; start < count; start += kLanes) {
    const int n = static_cast<int>(std::min<std::size_t>(kLanes, count - start));
    add_packet(pass, i, cand ? cand + start : nullptr, j0 + start, n, ts.row.data(), ts, edges, true);
  }
  end_row(pass, i, ts.row.data(), ts);
}

}  // namespace attenuvis::visgraph::detail
