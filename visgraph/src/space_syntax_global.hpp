// Global measures from step depths (space_syntax.hpp's definitions).
// Internal to the space-syntax files.
#pragma once

#include "space_syntax_measures.hpp"

#include <cstdint>
#include <vector>

namespace attenuvis::visgraph::space_syntax_detail {

// Hillier & Hanson's D-value of n nodes (Krüger 1989, via Teklenburg et
// al. 1993) and depthmapX's P-value.
double d_value(double n);
double p_value(double n);

// The measures of one origin from the nodes at each depth (at_depth[0] = 1,
// the origin), -1 where space_syntax.hpp says so.
struct DepthMeasures {
  double node_count = 0, mean_depth = -1, integration_hh = -1, integration_pvalue = -1, integration_tekl = -1,
         entropy = -1, relativised_entropy = -1;
};
DepthMeasures depth_measures(const std::vector<std::uint32_t>& at_depth);

// Every owned origin's measures within `radius` steps (0: unlimited), and
// the nodes at depth 2 (for controllability; computed whatever the radius
// when depth_two).
struct GlobalColumns {
  std::vector<double> node_count, mean_depth, integration_hh, integration_pvalue, integration_tekl, entropy,
      relativised_entropy, at_depth_two;
};
GlobalColumns global_measures(const Storage& g, int radius, bool depth_two, const Owned& owned, int threads);

}  // namespace attenuvis::visgraph::space_syntax_detail
