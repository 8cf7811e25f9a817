// The per-node computations behind space_syntax.hpp's local, weighted,
// metric and through-vision measures, on one graph G_k in internal order.
// Each fills the nodes that `owned` selects (one process's share) and leaves
// the others at +0.0.  Internal to the space-syntax files.
#pragma once

#include "space_syntax_graph.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace attenuvis::visgraph::space_syntax_detail {

// Which nodes this process computes: blocks of kOwnedBlock consecutive
// nodes (one BFS sweep), block b to process b mod count.
constexpr std::size_t kOwnedBlock = 512;
struct Owned {
  int index = 0, count = 1;
  bool operator()(std::size_t i) const { return static_cast<int>((i / kOwnedBlock) % count) == index; }
};

// Runs body(begin, end) over [0, n) in blocks of kOwnedBlock nodes on the
// given number of threads (0: all), skipping blocks another process owns.
void for_owned_blocks(std::size_t n, const Owned& owned, int threads,
                      const std::function<void(std::size_t, std::size_t)>& body);

struct LocalColumns {
  std::vector<double> connectivity, first_moment, second_moment;
  std::vector<double> clustering, control;
  // Neighbours j of i that another neighbour of i sees (|N(j) & N(i)| > 0):
  // with the nodes at depth 2 they make controllability's set.
  std::vector<double> linked_neighbours;
};
LocalColumns local_measures(const Storage& g, const Owned& owned, bool clustering, int threads);

struct WeightedColumns {
  std::vector<double> sum, first_moment, control, clustering;
};
// sum and first_moment always; control and clustering when asked.  The
// sum S_S is computed for every node (control reads its neighbours').
WeightedColumns weighted_measures(const Storage& g, double sigma, const Owned& owned, bool control,
                                  bool clustering, int threads);

// Shortest-path lengths (Dijkstra, edge length d) from every owned origin:
// visit(origin, lengths) with lengths[j] = l_ij (infinity where j is not
// reached); `lengths` is the calling thread's buffer.
void shortest_paths(const Storage& g, const Owned& owned, int threads,
                    const std::function<void(std::size_t, const std::vector<double>&)>& visit);

// Through vision on every condition's G_k at once: lines of G (owned rows
// i, partners j > i) with C = exp(-sigma_k d) >= eps count in condition k.
// counts[k][node], weighted[k][node] (fixed point, units of 2^-32).
struct ThroughVision {
  std::vector<std::vector<std::int64_t>> counts, weighted;
};
constexpr double kThroughVisionScale = 4294967296.0;  // 2^32
ThroughVision through_vision(const Storage& g, double spacing, const std::vector<double>& sigmas, double eps,
                             const Owned& owned, int threads);

// C_ij >= eps (eps = 0: every line of sight).
inline bool kept_line(double sigma, double d, double eps) { return eps <= 0 || std::exp(-sigma * d) >= eps; }

}  // namespace attenuvis::visgraph::space_syntax_detail
