// The per-node computations behind space_syntax.hpp's local, weighted,
// metric and through-vision measures, on one graph G_k in internal order.
// Each fills the nodes that `owned` selects (one process's share) and leaves
// the others at +0.0.  Internal to the space-syntax files.
#pragma once

#include "space_syntax_graph.hpp"

#include <atomic>
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
  const std::atomic<bool>* cancel = nullptr;  // set: blocks not yet started are skipped
  bool operator()(std::size_t i) const { return static_cast<int>((i / kOwnedBlock) % count) == index; }
  bool cancelled() const { return cancel && cancel->load(); }
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
// For each sigma (weathers that share this graph): sum and first_moment
// always, control and clustering when asked.  The sum S_S is computed for
// every node (control reads its neighbours').
std::vector<WeightedColumns> weighted_measures(const Storage& g, const std::vector<double>& sigmas, const Owned& owned,
                                              bool control, bool clustering, int threads);

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

// C_ij = exp(-sigma d) >= eps (eps = 0: every line of sight).  Decided by
// d against R = ln(1/eps)/sigma, except within a relative 1e-9 of R, where
// the roundings of exp and of R could disagree and exp itself decides.
class Threshold {
 public:
  Threshold(double sigma, double eps) : sigma_(sigma), eps_(eps) {
    every_ = eps <= 0 || sigma <= 0;
    const double r = every_ ? 0.0 : std::log(1.0 / eps) / sigma;
    low_ = r * (1 - 1e-9);
    high_ = r * (1 + 1e-9);
  }
  bool keeps(double d) const {
    if (every_ || d < low_) return true;
    if (d > high_) return false;
    return std::exp(-sigma_ * d) >= eps_;
  }

 private:
  double sigma_, eps_, low_ = 0, high_ = 0;
  bool every_ = true;
};

// c[t] = exp(-sigma d[t]) for t < n, to about 1 ulp (a vectorised
// exponential: Cody-Waite reduction and a degree-13 Taylor polynomial; see
// space_syntax_contrast.cpp), the same bits on every instruction set.
void contrasts(double sigma, const double* d, double* c, std::size_t n);

// A row's neighbours and their distances, gathered once for the sums over it.
struct Row {
  std::vector<std::uint32_t> partner;
  std::vector<double> distance, contrast;
  void gather(const Storage& g, std::size_t i) {
    partner.clear();
    distance.clear();
    for_each_neighbour(g, i, [&](std::uint32_t j) {
      partner.push_back(j);
      distance.push_back(g.distance(i, j));
    });
  }
  // contrast[t] = exp(-sigma distance[t]).
  void weigh(double sigma) {
    contrast.resize(distance.size());
    contrasts(sigma, distance.data(), contrast.data(), distance.size());
  }
};

}  // namespace attenuvis::visgraph::space_syntax_detail
