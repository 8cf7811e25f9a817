// Combining the shares of a visibility pass run on several processes
// (PassShare in visibility.hpp; the culled pass is shared by
// PairCulling::traverse_share).  Internal to the visgraph library.
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

// Every share's accumulators, pruned counts and counters summed, maxima
// maximised (PassShare::combine): integers, so exactly the one-process totals.
void combine_shares(const PassShare& share, std::vector<std::int64_t>& total, std::vector<double>& max_distance,
                    std::vector<std::uint32_t>& pruned, VisibilityResult& result);

}  // namespace attenuvis::visgraph::detail
