// What a visibility pass accepts: its options, its node sets, and the range
// within which its fixed-point sums are exact.  Internal to the visgraph
// library (visibility.cpp checks every pass with it before any work).
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include "node_points.hpp"

namespace attenuvis::visgraph::detail {

// Throws std::invalid_argument saying what is wrong: a sigma that is not
// finite and >= 0, a prune_below outside [0, 1), an empty node or target set,
// more than 2^32 nodes, a share that does not exist, or a run whose contrast
// or distance sums could overflow their 64-bit fixed point.
void check_pass_input(const Points& sources, const Points& partners, bool symmetric, const VisibilityOptions& options);

}  // namespace attenuvis::visgraph::detail
