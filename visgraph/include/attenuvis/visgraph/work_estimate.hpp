// What a visibility pass will cost, known before it is spent: the pairs it
// will consider and the memory its accumulators take, so that a caller can
// refuse a run that would take days or more memory than the machine has.
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace attenuvis::visgraph {

// Pairs above this are refused by default (attenuvis vg --allow-large lifts
// it): at the ~10^7 pairs/s of a few cores that is minutes of work.
constexpr double kDefaultMaxPairs = 2e9;

// The work a pass would do: nodes, pairs and bytes of accumulators.
struct WorkEstimate {
  std::size_t nodes = 0;
  std::size_t targets = 0;        // 0 for all-to-all
  double radius = 0;              // m: partners farther are never considered (inf: none)
  double pairs = 0;               // pairs considered: an upper bound on the rays cast
  double bytes = 0;               // accumulators, points and search structures
  int threads = 1;                // worker threads the pass will use
};

// The estimate for all_to_all (targets == nullptr) or to_targets.  With a
// finite radius (max_distance, or pruning) the pairs are counted exactly
// as the pass finds candidates: partners within the radius along x.
// O((N + M) log(N + M)).
WorkEstimate estimate_work(const std::vector<Eigen::Vector3d>& sources, const std::vector<Eigen::Vector3d>* targets,
                           const VisibilityOptions& options);

// Bytes of memory of this machine (0 if unknown).
double physical_memory_bytes();

}  // namespace attenuvis::visgraph
