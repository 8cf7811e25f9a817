// Local and contrast-weighted measures (space_syntax_measures.hpp).  Every
// sum over a node's neighbours runs in increasing neighbour index on the
// thread that owns the node, so the results do not depend on the threads.
#include "space_syntax_measures.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace attenuvis::visgraph::space_syntax_detail {

void for_owned_blocks(std::size_t n, const Owned& owned, int threads,
                      const std::function<void(std::size_t, std::size_t)>& body) {
  const std::size_t blocks = (n + kOwnedBlock - 1) / kOwnedBlock;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t b = r.begin(); b != r.end(); ++b) {
        const std::size_t begin = b * kOwnedBlock;
        if (owned(begin) && !owned.cancelled()) body(begin, std::min(n, begin + kOwnedBlock));
      }
    });
  });
}

namespace {
// Common-neighbour counts of every edge, summed per node: sum_j |N(i) & N(j)|
// and the neighbours with a non-zero count.  With one process each edge is
// counted once, from its lower end, and added to both (integer atomics: the
// totals do not depend on the order); otherwise each owned node counts its
// own edges.
void common_counts(const Storage& g, const Owned& owned, int threads, std::vector<std::uint64_t>& common,
                   std::vector<std::uint64_t>& linked) {
  common.assign(g.n, 0);
  linked.assign(g.n, 0);
  const bool once = owned.count == 1;
  for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        if (once && j < i) return;
        const std::uint64_t c = common_neighbours(g, i, j);
        const std::uint64_t l = c > 0 ? 1 : 0;
        if (!once) {
          common[i] += c, linked[i] += l;
          return;
        }
        __atomic_fetch_add(&common[i], c, __ATOMIC_RELAXED);
        __atomic_fetch_add(&common[j], c, __ATOMIC_RELAXED);
        __atomic_fetch_add(&linked[i], l, __ATOMIC_RELAXED);
        __atomic_fetch_add(&linked[j], l, __ATOMIC_RELAXED);
      });
  });
}
}  // namespace

LocalColumns local_measures(const Storage& g, const Owned& owned, bool clustering, int threads) {
  LocalColumns c;
  for (auto* v : {&c.connectivity, &c.first_moment, &c.second_moment, &c.clustering, &c.control, &c.linked_neighbours})
    v->assign(g.n, 0.0);
  std::vector<std::uint64_t> common, linked;
  if (clustering) common_counts(g, owned, threads, common, linked);
  for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t k = g.degree[i];
      double first = 0, second = 0, control = 0;
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        const double d = g.distance(i, j);
        first += d;
        second += d * d;
        control += 1.0 / g.degree[j];
      });
      c.connectivity[i] = k;
      c.first_moment[i] = first;
      c.second_moment[i] = second;
      // depthmapX writes -1 for a node with at most one neighbour.
      c.control[i] = k > 1 ? control : -1.0;
      if (clustering) {
        c.clustering[i] = k > 1 ? static_cast<double>(common[i]) / (static_cast<double>(k) * (k - 1.0)) : -1.0;
        c.linked_neighbours[i] = static_cast<double>(linked[i]);
      }
    }
  });
  return c;
}

namespace {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ATTENUVIS_DOT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_DOT_CLONES
#endif

// sum_h a[h] b[h] over [from, to), in 8 interleaved partial sums added in a
// fixed order: the same bits for every instruction set.
ATTENUVIS_DOT_CLONES double dot(const double* a, const double* b, std::size_t from, std::size_t to) {
  double acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  std::size_t h = from;
  for (; h + 8 <= to; h += 8)
    for (int l = 0; l < 8; ++l) acc[l] += a[h + l] * b[h + l];
  for (int l = 0; h < to; ++h, ++l) acc[l] += a[h] * b[h];
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

// Onnela's clustering [On05] with w = C / max C: the cube roots of the
// normalised weights, a_ij = exp(-sigma (d_ij - d_min) / 3), held as a dense
// N x N matrix (zeros off the graph), and for each node
//   sum_{j in N(i)} a_ij sum_{h} a_ih a_jh  = sum_j a_ij (A_i . A_j),
// the inner sum over the span of indices both rows can hold.
std::vector<double> onnela_clustering(const Storage& g, double sigma, const Owned& owned, int threads) {
  const std::size_t n = g.n;
  double d_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    for_each_neighbour(g, i, [&](std::uint32_t j) {
      if (j > i) d_min = std::min(d_min, g.distance(i, j));
    });
  std::vector<double> a(n * n, 0.0);
  std::vector<std::uint32_t> lo(n, 0), hi(n, 0);  // [lo, hi): where row i can be non-zero
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      bool first = true;
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        a[i * n + j] = std::exp(-sigma * (g.distance(i, j) - d_min) / 3.0);
        if (first) lo[i] = j, first = false;
        hi[i] = j + 1;
      });
    });
  });
  std::vector<double> out(n, 0.0);
  for_owned_blocks(n, owned, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t k = g.degree[i];
      if (k <= 1) {
        out[i] = -1.0;
        continue;
      }
      double total = 0;
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        const std::size_t from = std::max(lo[i], lo[j]), to = std::min(hi[i], hi[j]);
        if (from < to) total += a[i * n + j] * dot(a.data() + i * n, a.data() + std::size_t{j} * n, from, to);
      });
      out[i] = total / (static_cast<double>(k) * (k - 1.0));
    }
  });
  return out;
}
}  // namespace

std::vector<WeightedColumns> weighted_measures(const Storage& g, const std::vector<double>& sigmas, const Owned& owned,
                                              bool control, bool clustering, int threads) {
  const std::size_t K = sigmas.size();
  std::vector<WeightedColumns> c(K);
  for (WeightedColumns& w : c) w.sum.assign(g.n, 0.0), w.first_moment.assign(g.n, 0.0);
  tbb::enumerable_thread_specific<Row> rows;
  // S_S of every node (control reads the neighbours'), the moment of the owned ones.
  for_owned_blocks(g.n, Owned{0, 1, owned.cancel}, threads, [&](std::size_t begin, std::size_t end) {
    Row& row = rows.local();
    for (std::size_t i = begin; i < end; ++i) {
      row.gather(g, i);
      for (std::size_t k = 0; k < K; ++k) {
        row.weigh(sigmas[k]);
        double sum = 0, moment = 0;
        for (std::size_t t = 0; t < row.distance.size(); ++t)
          sum += row.contrast[t], moment += row.contrast[t] * row.distance[t];
        c[k].sum[i] = sum;
        c[k].first_moment[i] = owned(i) ? moment : 0.0;
      }
    }
  });
  if (control) {
    for (WeightedColumns& w : c) w.control.assign(g.n, 0.0);
    for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
      Row& row = rows.local();
      for (std::size_t i = begin; i < end; ++i) {
        row.gather(g, i);
        for (std::size_t k = 0; k < K; ++k) {
          row.weigh(sigmas[k]);
          double total = 0;
          for (std::size_t t = 0; t < row.distance.size(); ++t) total += row.contrast[t] / c[k].sum[row.partner[t]];
          c[k].control[i] = g.degree[i] > 1 ? total : -1.0;
        }
      }
    });
  }
  for (std::size_t k = 0; k < K; ++k) {
    if (clustering) c[k].clustering = onnela_clustering(g, sigmas[k], owned, threads);
    // Only the owned nodes' sums leave this process (the others were needed
    // here only for control).
    for (std::size_t i = 0; i < g.n; ++i)
      if (!owned(i)) c[k].sum[i] = 0.0;
  }
  return c;
}

}  // namespace attenuvis::visgraph::space_syntax_detail
