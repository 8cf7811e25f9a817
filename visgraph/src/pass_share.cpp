// Splitting a pass into shares and combining them (pass_share.hpp).
#include "pass_share.hpp"

#include <algorithm>
#include <stdexcept>

namespace attenuvis::visgraph::detail {

void combine_shares(const PassShare& share, std::vector<std::int64_t>& total, std::vector<double>& max_distance,
                    std::vector<std::uint32_t>& pruned, VisibilityResult& result) {
  std::vector<std::int64_t> sums(total);
  sums.insert(sums.end(), pruned.begin(), pruned.end());
  for (std::uint64_t counter : {result.pairs_cast, result.pairs_visible, result.coincident_pairs,
                                result.pairs_culled_visible, result.pairs_culled_blocked})
    sums.push_back(static_cast<std::int64_t>(counter));
  const std::size_t length = sums.size(), maxima = max_distance.size();
  share.combine(sums, max_distance);
  if (sums.size() != length || max_distance.size() != maxima)
    throw std::logic_error("visibility: the combine step changed the length of the accumulators");
  std::copy(sums.begin(), sums.begin() + static_cast<std::ptrdiff_t>(total.size()), total.begin());
  for (std::size_t i = 0; i < pruned.size(); ++i) pruned[i] = static_cast<std::uint32_t>(sums[total.size() + i]);
  const std::int64_t* counters = sums.data() + total.size() + pruned.size();
  result.pairs_cast = static_cast<std::uint64_t>(counters[0]);
  result.pairs_visible = static_cast<std::uint64_t>(counters[1]);
  result.coincident_pairs = static_cast<std::uint64_t>(counters[2]);
  result.pairs_culled_visible = static_cast<std::uint64_t>(counters[3]);
  result.pairs_culled_blocked = static_cast<std::uint64_t>(counters[4]);
}

}  // namespace attenuvis::visgraph::detail
