// The raw Embree ceiling of the benchmarks (detail/raw_occlusion.hpp): the
// engine's rays, occlusion only, no scoring.
#include <attenuvis/visgraph/detail/raw_occlusion.hpp>

#include "node_points.hpp"
#include "pair_packet.hpp"
#include "scene_access.hpp"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <limits>

namespace attenuvis::visgraph {

using detail::kLanes;
using detail::PairPacket;
using detail::Points;
using detail::sorted_by_x;
using detail::to_local;

std::uint64_t raw_visible_pairs(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes, int threads,
                                RawMethod method) {
  // The same directed rays as all_to_all: nodes in x order, each pair cast
  // from the earlier one (see plan_pass).
  std::vector<std::uint32_t> order;
  const Points P = sorted_by_x(to_local(scene, eyes, "node"), order);
  const RTCScene rtc = detail::SceneAccess::embree(scene);
  const std::size_t N = P.size();
  std::atomic<std::uint64_t> visible{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 1), [&](const tbb::blocked_range<std::size_t>& range) {
      std::uint64_t seen = 0;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      if (method == RawMethod::packets16) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      PairPacket packet;
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        // The engine's rays (same policy, same setup code), in contiguous
        // x-order packets of 16 (the fastest raw loop); single rays cast each
        // lane with rtcOccluded1.
        for (std::size_t start = i + 1; start < N; start += kLanes) {
          const int n = static_cast<int>(std::min<std::size_t>(kLanes, N - start));
          detail::build_packet(P.x[i], P.y[i], P.z[i], P.x.data() + start, P.y.data() + start, P.z.data() + start, n,
                               std::numeric_limits<double>::infinity(), packet);
          if (method == RawMethod::packets16) {
            if (packet.cast) rtcOccluded16(packet.valid, rtc, &context, &packet.ray);
          } else {
            for (int l = 0; l < kLanes; ++l) {
              if (!packet.valid[l]) continue;
              RTCRay ray{};
              ray.org_x = packet.ray.org_x[l];
              ray.org_y = packet.ray.org_y[l];
              ray.org_z = packet.ray.org_z[l];
              ray.dir_x = packet.ray.dir_x[l];
              ray.dir_y = packet.ray.dir_y[l];
              ray.dir_z = packet.ray.dir_z[l];
              ray.tnear = packet.ray.tnear[l];
              ray.tfar = packet.ray.tfar[l];
              ray.mask = 0xFFFFFFFFu;
              rtcOccluded1(rtc, &context, &ray);
              packet.ray.tfar[l] = ray.tfar;
            }
          }
          for (int l = 0; l < kLanes; ++l) seen += packet.valid[l] ? packet.ray.tfar[l] >= 0 : packet.visible[l] != 0;
        }
      }
      visible += seen;
    });
  });
  return visible.load();
}

}  // namespace attenuvis::visgraph
