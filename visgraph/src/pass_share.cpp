// Splitting a pass into shares and combining them (pass_share.hpp).
#include "pass_share.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace attenuvis::visgraph::detail {

LeafRange share_leaves(const PairCulling& culling, const PassShare& share) {
  const std::size_t L = culling.leaf_count();
  if (share.count == 1) return LeafRange{0, L, 1};
  std::vector<std::uint64_t> cost(L + 1, 0), pairs(L, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, L, 16), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<PairCulling::Block> blocks;
    for (std::size_t leaf = range.begin(); leaf != range.end(); ++leaf) {
      std::size_t count = 0;
      const std::uint32_t* rows = culling.leaf_rows(leaf, count);
      culling.partner_blocks(leaf, blocks);
      for (const PairCulling::Block& block : blocks) {
        std::size_t n = 0;
        const std::uint32_t* partners = culling.leaf_rows(block.leaf, n);
        if (n == 0 || count == 0 || partners[n - 1] <= rows[0]) continue;  // every partner before every row
        std::uint64_t after = 0;  // pairs (row, partner) with the partner after the row
        if (partners[0] > rows[count - 1])
          after = static_cast<std::uint64_t>(count) * n;
        else
          for (std::size_t r = 0; r < count; ++r)
            after += static_cast<std::uint64_t>(partners + n - std::upper_bound(partners, partners + n, rows[r]));
        pairs[leaf] += after;
        cost[leaf + 1] += after * (block.verdict == Verdict::cast ? 4 : 1);
      }
    }
  });
  for (std::size_t l = 0; l < L; ++l) cost[l + 1] += cost[l];
  const auto begin_of = [&](int k) {
    const std::uint64_t target = static_cast<std::uint64_t>(
        static_cast<long double>(cost[L]) * k / share.count);
    return static_cast<std::size_t>(std::lower_bound(cost.begin(), cost.end(), target) - cost.begin());
  };
  LeafRange range;
  range.first = share.index == 0 ? 0 : std::min(begin_of(share.index), L);
  range.last = share.index + 1 == share.count ? L : std::min(begin_of(share.index + 1), L);
  range.last = std::max(range.first, range.last);
  std::uint64_t all = 0, mine = 0;
  for (std::size_t l = 0; l < L; ++l) all += pairs[l], mine += l >= range.first && l < range.last ? pairs[l] : 0;
  range.scale = mine > 0 ? static_cast<double>(all) / static_cast<double>(mine) : 1.0;
  return range;
}

void combine_shares(const PassShare& share, std::vector<std::int64_t>& total, std::vector<double>& max_distance,
                    std::vector<std::uint32_t>& pruned, VisibilityResult& result) {
  std::vector<std::int64_t> sums(total);
  sums.insert(sums.end(), pruned.begin(), pruned.end());
  for (std::uint64_t counter : {result.pairs_cast, result.pairs_visible, result.coincident_pairs})
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
}

}  // namespace attenuvis::visgraph::detail
