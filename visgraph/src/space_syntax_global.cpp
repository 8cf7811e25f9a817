// The global measures of space_syntax.hpp from the depth counts of the
// bit-parallel sweeps (space_syntax_depth.hpp), one sweep per block of 512
// origins, and their formulas [HH84; Te93; dmX vgavisualglobal, pafmath.h].
#include "space_syntax_global.hpp"

#include "space_syntax_depth.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>

namespace attenuvis::visgraph::space_syntax_detail {

double d_value(double n) { return 2.0 * (n * (std::log2((n + 2.0) / 3.0) - 1.0) + 1.0) / ((n - 1.0) * (n - 2.0)); }
double p_value(double n) { return 2.0 * (n - std::log2(n) - 1.0) / ((n - 1.0) * (n - 2.0)); }

DepthMeasures depth_measures(const std::vector<std::uint32_t>& at_depth) {
  DepthMeasures m;
  std::uint64_t n = 0, total = 0;
  for (std::size_t d = 0; d < at_depth.size(); ++d) n += at_depth[d], total += d * std::uint64_t{at_depth[d]};
  m.node_count = static_cast<double>(n);
  if (n <= 1) return m;  // every other measure stays -1
  const double nodes = static_cast<double>(n), td = static_cast<double>(total);
  const double md = td / (nodes - 1.0);
  m.mean_depth = md;
  if (n > 2 && md > 1.0) {
    const double ra = 2.0 * (md - 1.0) / (nodes - 2.0);
    m.integration_hh = d_value(nodes) / ra;
    m.integration_pvalue = p_value(nodes) / ra;
    // ln((n - 2)/2) / ln(TD - n + 1), where the logarithm's argument exceeds 1.
    if (td - nodes + 1.0 > 1.0) m.integration_tekl = std::log(0.5 * (nodes - 2.0)) / std::log(td - nodes + 1.0);
  }
  double entropy = 0, relativised = 0, factorial = 1;
  for (std::size_t d = 1; d < at_depth.size(); ++d) {
    if (at_depth[d] == 0) continue;
    const double p = at_depth[d] / (nodes - 1.0);
    entropy -= p * std::log2(p);
    // q_d = MD^d e^{-MD} / (d + 1)!; depths are consecutive, so the running
    // product is (d + 1)! at every level that has nodes.
    factorial *= static_cast<double>(d + 1);
    const double q = std::pow(md, static_cast<double>(d)) / factorial * std::exp(-md);
    relativised += p * std::log2(p / q);
  }
  m.entropy = entropy;
  m.relativised_entropy = relativised;
  return m;
}

GlobalColumns global_measures(const Storage& g, int radius, bool depth_two, const Owned& owned, int threads) {
  GlobalColumns c;
  for (auto* v : {&c.node_count, &c.mean_depth, &c.integration_hh, &c.integration_pvalue, &c.integration_tekl,
                  &c.entropy, &c.relativised_entropy, &c.at_depth_two})
    v->assign(g.n, 0.0);
  // Controllability needs the nodes two steps away whatever the radius.
  const int depth = radius > 0 ? std::max(radius, depth_two ? 2 : 0) : 0;
  tbb::enumerable_thread_specific<DepthSweeper> sweepers([&] { return DepthSweeper(g); });
  static_assert(kOwnedBlock == kSweepOrigins, "a process owns whole sweeps");
  for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
    SweepDepths sweep;
    sweepers.local().run(begin, end - begin, depth, sweep);
    std::vector<std::uint32_t> at_depth;
    for (std::size_t b = 0; b < sweep.origins; ++b) {
      const std::size_t levels = radius > 0 ? std::min<std::size_t>(sweep.levels, radius + 1) : sweep.levels;
      at_depth.resize(levels);
      for (std::size_t d = 0; d < levels; ++d) at_depth[d] = sweep.at(d, b);
      const DepthMeasures m = depth_measures(at_depth);
      const std::size_t i = begin + b;
      c.node_count[i] = m.node_count;
      c.mean_depth[i] = m.mean_depth;
      c.integration_hh[i] = m.integration_hh;
      c.integration_pvalue[i] = m.integration_pvalue;
      c.integration_tekl[i] = m.integration_tekl;
      c.entropy[i] = m.entropy;
      c.relativised_entropy[i] = m.relativised_entropy;
      c.at_depth_two[i] = sweep.at(2, b);
    }
  });
  return c;
}

}  // namespace attenuvis::visgraph::space_syntax_detail
