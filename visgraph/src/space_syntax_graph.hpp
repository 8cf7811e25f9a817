// The lines of sight as the space-syntax measures read them: an undirected
// simple graph over nodes renumbered along a Hilbert curve of their plan
// position (so that a block of consecutive nodes is a patch of ground: the
// 512 origins of one bit-parallel BFS sweep lie together, and a node's
// neighbours fill few words of its bit row), held either as
//   bit rows   N x ceil(N/64) words, with each row's first and last non-zero
//              word (dense graphs: 1 bit per pair), or
//   CSR        sorted uint32 neighbour lists (sparse graphs: 8 bytes per edge).
// Internal to the space-syntax files.
#pragma once

#include <attenuvis/visgraph/space_syntax.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace attenuvis::visgraph {

struct VisibilityGraph::Storage {
  std::size_t n = 0;
  std::uint64_t m = 0;                  // undirected edges
  std::vector<std::uint32_t> caller;    // caller[internal] = the caller's node index
  std::vector<std::uint32_t> internal;  // internal[caller] = internal index
  std::vector<Eigen::Vector3d> position;  // world frame, internal order
  std::vector<std::uint32_t> degree;

  bool dense = true;
  std::size_t words = 0;                // per bit row
  std::vector<std::uint64_t> bits;      // n * words
  std::vector<std::uint32_t> first_word, last_word;  // first > last: empty row

  std::vector<std::uint64_t> offset;    // CSR: n + 1
  std::vector<std::uint32_t> adjacency;

  const std::uint64_t* row(std::size_t i) const { return bits.data() + i * words; }

  // d_ij as space_syntax.hpp defines it (no contraction: the space-syntax
  // files are compiled with -ffp-contract=off).
  double distance(std::size_t i, std::size_t j) const {
    const double dx = position[i].x() - position[j].x();
    const double dy = position[i].y() - position[j].y();
    const double dz = position[i].z() - position[j].z();
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  double bytes() const;
};

namespace space_syntax_detail {

using Storage = VisibilityGraph::Storage;

inline int lowest_bit(std::uint64_t x) { return __builtin_ctzll(x); }

// f(j) for every neighbour j of i, in increasing j.
template <class F>
void for_each_neighbour(const Storage& g, std::size_t i, F&& f) {
  if (g.dense) {
    const std::uint64_t* r = g.row(i);
    for (std::size_t w = g.first_word[i]; w <= g.last_word[i] && g.first_word[i] <= g.last_word[i]; ++w)
      for (std::uint64_t x = r[w]; x; x &= x - 1) f(static_cast<std::uint32_t>(w * 64 + lowest_bit(x)));
  } else {
    for (std::uint64_t p = g.offset[i]; p < g.offset[i + 1]; ++p) f(g.adjacency[p]);
  }
}

// The same, stopping as soon as f returns false.
template <class F>
void for_each_neighbour_until(const Storage& g, std::size_t i, F&& f) {
  if (g.dense) {
    if (g.first_word[i] > g.last_word[i]) return;
    const std::uint64_t* r = g.row(i);
    for (std::size_t w = g.first_word[i]; w <= g.last_word[i]; ++w)
      for (std::uint64_t x = r[w]; x; x &= x - 1)
        if (!f(static_cast<std::uint32_t>(w * 64 + lowest_bit(x)))) return;
  } else {
    for (std::uint64_t p = g.offset[i]; p < g.offset[i + 1]; ++p)
      if (!f(g.adjacency[p])) return;
  }
}

// |N(i) & N(j)|.
std::uint64_t common_neighbours(const Storage& g, std::size_t i, std::size_t j);

// Renumbering along a Hilbert curve of (x, y) (ties by the caller's index):
// order[internal] = caller index.
std::vector<std::uint32_t> hilbert_order(const std::vector<Eigen::Vector3d>& eyes);

// A graph with the same nodes and order, holding the edges of `g` for which
// keep(i, j) (called once per edge, i < j) is true.
template <class Keep>
Storage thinned(const Storage& g, Keep&& keep);

// Builds the storage from edges given in internal indices (i != j, each
// pair once): rows of bits set by set_edge, or an edge list for CSR.
class StorageBuilder {
 public:
  StorageBuilder(const std::vector<Eigen::Vector3d>& eyes, bool dense);
  void add(std::uint32_t caller_i, std::uint32_t caller_j);
  // The pairs collected so far as words (bit rows) or packed pairs (CSR),
  // for joining the shares of several processes.
  std::vector<std::uint64_t>& words() { return dense_ ? bits_ : pairs_; }
  bool dense() const { return dense_; }
  Storage finish();

 private:
  bool dense_;
  std::size_t n_ = 0, row_words_ = 0;
  std::vector<std::uint32_t> caller_, internal_;
  std::vector<Eigen::Vector3d> position_;
  std::vector<std::uint64_t> bits_;   // dense: the bit rows as they fill
  std::vector<std::uint64_t> pairs_;  // CSR: (i << 32 | j), i < j, internal indices
};

// Completes a storage whose bits (dense) or offset/adjacency (CSR) are set:
// degrees, spans of non-zero words, edge count.
void finish_storage(Storage& g);

template <class Keep>
Storage thinned(const Storage& g, Keep&& keep) {
  Storage t;
  t.n = g.n;
  t.caller = g.caller;
  t.internal = g.internal;
  t.position = g.position;
  t.dense = g.dense;
  t.words = g.words;
  if (g.dense) {
    t.bits.assign(g.bits.size(), 0);
    for (std::size_t i = 0; i < g.n; ++i)
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        if (j > i && keep(i, j)) {
          t.bits[i * t.words + j / 64] |= std::uint64_t{1} << (j % 64);
          t.bits[j * t.words + i / 64] |= std::uint64_t{1} << (i % 64);
        }
      });
  } else {
    std::vector<std::uint32_t> count(g.n, 0);
    std::vector<std::uint8_t> kept(g.adjacency.size(), 0);
    for (std::size_t i = 0; i < g.n; ++i)
      for (std::uint64_t p = g.offset[i]; p < g.offset[i + 1]; ++p) {
        const std::uint32_t j = g.adjacency[p];
        if (j > i && keep(i, j)) kept[p] = 1, ++count[i], ++count[j];
      }
    t.offset.assign(g.n + 1, 0);
    for (std::size_t i = 0; i < g.n; ++i) t.offset[i + 1] = t.offset[i] + count[i];
    t.adjacency.resize(t.offset[g.n]);
    std::vector<std::uint64_t> at(t.offset.begin(), t.offset.end() - 1);
    // Rows fill in increasing partner order: partner j < i arrives from row
    // j (visited earlier), partner j > i from row i itself, in order.
    for (std::size_t i = 0; i < g.n; ++i)
      for (std::uint64_t p = g.offset[i]; p < g.offset[i + 1]; ++p) {
        const std::uint32_t j = g.adjacency[p];
        if (j > i && kept[p]) t.adjacency[at[i]++] = j, t.adjacency[at[j]++] = static_cast<std::uint32_t>(i);
      }
  }
  finish_storage(t);
  return t;
}

}  // namespace space_syntax_detail
}  // namespace attenuvis::visgraph
