// One process's share of a visibility pass run on several processes
// (PassShare in visibility.hpp).  Internal to the visgraph library.
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include "pair_culling.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

// The leaves [first, last) whose rows this process accumulates (PassShare):
// a contiguous range balanced by estimated cost, a cast pair 4 units, a pair
// culled in sight 1 (scored without a ray), a blocked pair 0.  Integer costs
// counted per leaf, so every process computes the same ranges whatever its
// thread schedule.  `scale`: all unblocked pairs over the share's, for the
// progress estimate.
struct LeafRange {
  std::size_t first = 0, last = 0;
  double scale = 1;
};

LeafRange share_leaves(const PairCulling& culling, const PassShare& share);

// Every share's accumulators, pruned counts and counters summed, maxima
// maximised (PassShare::combine): integers, so exactly the one-process totals.
void combine_shares(const PassShare& share, std::vector<std::int64_t>& total, std::vector<double>& max_distance,
                    std::vector<std::uint32_t>& pruned, VisibilityResult& result);

}  // namespace attenuvis::visgraph::detail
