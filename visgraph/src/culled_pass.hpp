// All-to-all without a candidate radius, with or without culling: rows
// against leaf clusters (pair_culling.hpp), the nodes laid out leaf after
// leaf.  Internal to the visgraph library (visibility.cpp).
//
// Layout.  The pass's rows are the nodes in x order (which end casts a
// pair, and the canonical packets, are defined on it: visibility.hpp), but
// its coordinates and accumulators are kept in leaf order, so that the
// partners of a row in one leaf, those after it in x order, are a
// contiguous run: a packet reads its partners' coordinates in place and
// credits them with vector adds, and a block of pairs decided in sight is
// scored as a dense block (visible_block.hpp), once per pair of leaves,
// crediting each node once per block.  With an edge sink, in-sight pairs go
// through packets without rays instead, so that edges come out row by row.
#pragma once

#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include "pass_rows.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::detail {

// Runs the pass on `pass` (rows: the nodes in x order; pass.caller maps
// them to the caller's indices) into the threads' accumulators, indexed by
// leaf-order position, and fills the culling's counts and timings in
// `result`.  Returns the caller's index of each position.
std::vector<std::uint32_t> run_culled_pass(const Scene& scene, const Pass& pass, const VisibilityOptions& options,
                                           tbb::enumerable_thread_specific<ThreadState>& states,
                                           VisibilityResult& result);

}  // namespace attenuvis::visgraph::detail
