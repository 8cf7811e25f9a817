// The ceiling the benchmarks measure the engine against: the same unordered
// pairs as all_to_all, cast as the same rays (same end, same epsilon
// policy: visibility.hpp), occlusion only, no scoring.  Not part of the
// public interface: for the benchmarks of validation/ only.
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace attenuvis::visgraph {

enum class RawMethod { single_rays, packets16 };

// Visible pairs of `eyes` (world frame) on `threads` worker threads
// (0 = all cores).
std::uint64_t raw_visible_pairs(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes, int threads,
                                RawMethod method);

}  // namespace attenuvis::visgraph
