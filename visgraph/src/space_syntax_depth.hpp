// Step depths on the space-syntax graph: the bit-parallel multi-source BFS
// behind every global measure, and the plain BFS of step depth from chosen
// origins and of connected components.  Internal to the space-syntax files.
#pragma once

#include "space_syntax_graph.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::space_syntax_detail {

// One sweep carries 512 origins: 8 words of bits per node, one bit per
// origin [Then et al. 2014].
constexpr std::size_t kSweepWords = 8;
constexpr std::size_t kSweepOrigins = 64 * kSweepWords;

// counts[d * kSweepOrigins + b]: nodes at step depth d from origin first + b
// (d = 0 is the origin itself), for d < levels.
struct SweepDepths {
  std::size_t first = 0, origins = 0, levels = 0;
  std::vector<std::uint32_t> counts;
  std::uint32_t at(std::size_t d, std::size_t b) const { return d < levels ? counts[d * kSweepOrigins + b] : 0; }
};

// Per-thread state of the sweeps: seen, frontier and next bits of every
// node (3 x 64 bytes per node), and one bit per node that says whether its
// frontier bits are non-zero.
class DepthSweeper {
 public:
  explicit DepthSweeper(const Storage& g);
  // Breadth-first search from the nodes [first, first + origins), origins
  // <= kSweepOrigins, to depth max_depth (0: until nothing new is reached).
  // Each level goes top-down (push: the frontier's neighbours) or bottom-up
  // (pull: each node not yet reached by every origin looks at its
  // neighbours until it has them all), whichever has less to read
  // [Beamer et al. 2012]; the depths are the same either way.
  void run(std::size_t first, std::size_t origins, int max_depth, SweepDepths& out);

 private:
  std::uint64_t push();
  std::uint64_t pull();
  // Moves next into frontier and seen; counts the new bits at depth d.
  bool settle(std::size_t d, SweepDepths& out, std::uint64_t& push_work, std::uint64_t& pull_work);

  const Storage& g_;
  std::vector<std::uint64_t> seen_, frontier_, next_;
  // active_[v / 64] bit v % 64: node v is on the frontier of some origin.
  // A pull skips every other neighbour without reading its 64 bytes (in
  // bit rows, a whole word of neighbours at a time); a push visits only
  // these nodes.
  std::vector<std::uint64_t> active_;
  std::uint64_t valid_[kSweepWords] = {};
};

// Depth of every node from the nearest origin (internal indices), -1 where
// none reaches it.
std::vector<int> step_depths(const Storage& g, const std::vector<std::uint32_t>& origins);

// The size of each node's connected component.
std::vector<std::uint32_t> component_sizes(const Storage& g, std::size_t* components = nullptr);

}  // namespace attenuvis::visgraph::space_syntax_detail
