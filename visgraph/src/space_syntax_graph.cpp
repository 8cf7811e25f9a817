// The space-syntax graph: Hilbert renumbering, bit rows or CSR, the
// collector that receives a pass's edges (space_syntax_graph.hpp).
#include "space_syntax_graph.hpp"

#include <attenuvis/io/check.hpp>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

double VisibilityGraph::Storage::bytes() const {
  return 8.0 * (bits.size() + offset.size()) + 4.0 * (adjacency.size() + first_word.size() + last_word.size() +
                                                      degree.size() + caller.size() + internal.size()) +
         24.0 * position.size();
}

VisibilityGraph::VisibilityGraph() : storage_(std::make_shared<Storage>()) {}
VisibilityGraph::VisibilityGraph(std::shared_ptr<const Storage> storage) : storage_(std::move(storage)) {}
std::size_t VisibilityGraph::nodes() const { return storage_->n; }
std::uint64_t VisibilityGraph::edges() const { return storage_->m; }
bool VisibilityGraph::bit_rows() const { return storage_->dense; }
double VisibilityGraph::bytes() const { return storage_->bytes(); }

namespace space_syntax_detail {

namespace {
// Position of (x, y) along the Hilbert curve filling a 2^16 x 2^16 grid
// (the classic rotate-and-reflect walk, one quadrant per level).
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t side = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = side / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) x = side - 1 - x, y = side - 1 - y;
      std::swap(x, y);
    }
  }
  return d;
}

std::uint64_t popcount(std::uint64_t x) { return static_cast<std::uint64_t>(__builtin_popcountll(x)); }

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// The word loop of common_neighbours with the popcnt instruction where the
// CPU has it (the baseline x86-64 target has none).
__attribute__((target("popcnt"))) std::uint64_t and_popcount_fast(const std::uint64_t* a, const std::uint64_t* b,
                                                                  std::size_t from, std::size_t to) {
  std::uint64_t c = 0;
  for (std::size_t w = from; w <= to; ++w) c += static_cast<std::uint64_t>(__builtin_popcountll(a[w] & b[w]));
  return c;
}
const bool kHasPopcnt = __builtin_cpu_supports("popcnt");
#endif

std::uint64_t and_popcount(const std::uint64_t* a, const std::uint64_t* b, std::size_t from, std::size_t to) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  if (kHasPopcnt) return and_popcount_fast(a, b, from, to);
#endif
  std::uint64_t c = 0;
  for (std::size_t w = from; w <= to; ++w) c += popcount(a[w] & b[w]);
  return c;
}
}  // namespace

std::uint64_t common_neighbours(const Storage& g, std::size_t i, std::size_t j) {
  if (g.dense) {
    const std::size_t from = std::max(g.first_word[i], g.first_word[j]);
    const std::size_t to = std::min(g.last_word[i], g.last_word[j]);
    if (from > to || g.first_word[i] > g.last_word[i] || g.first_word[j] > g.last_word[j]) return 0;
    return and_popcount(g.row(i), g.row(j), from, to);
  }
  const std::uint32_t *a = g.adjacency.data() + g.offset[i], *ae = g.adjacency.data() + g.offset[i + 1];
  const std::uint32_t *b = g.adjacency.data() + g.offset[j], *be = g.adjacency.data() + g.offset[j + 1];
  std::uint64_t c = 0;
  while (a != ae && b != be) {
    if (*a < *b) ++a;
    else if (*b < *a) ++b;
    else ++c, ++a, ++b;
  }
  return c;
}

std::vector<std::uint32_t> hilbert_order(const std::vector<Eigen::Vector3d>& eyes) {
  const std::size_t n = eyes.size();
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n == 0) return order;
  double x0 = eyes[0].x(), x1 = x0, y0 = eyes[0].y(), y1 = y0;
  for (const auto& e : eyes) x0 = std::min(x0, e.x()), x1 = std::max(x1, e.x()), y0 = std::min(y0, e.y()), y1 = std::max(y1, e.y());
  const double extent = std::max({x1 - x0, y1 - y0, 1e-9});
  const double scale = 65535.0 / extent;
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto qx = static_cast<std::uint32_t>(std::clamp((eyes[i].x() - x0) * scale, 0.0, 65535.0));
    const auto qy = static_cast<std::uint32_t>(std::clamp((eyes[i].y() - y0) * scale, 0.0, 65535.0));
    key[i] = hilbert_index(qx, qy);
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return key[a] != key[b] ? key[a] < key[b] : a < b;
  });
  return order;
}

StorageBuilder::StorageBuilder(const std::vector<Eigen::Vector3d>& eyes, bool dense) : dense_(dense), n_(eyes.size()) {
  if (n_ >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("space syntax: " + std::to_string(n_) + " nodes, more than 2^32 - 1");
  caller_ = hilbert_order(eyes);
  internal_.resize(n_);
  position_.resize(n_);
  for (std::size_t k = 0; k < n_; ++k) internal_[caller_[k]] = static_cast<std::uint32_t>(k), position_[k] = eyes[caller_[k]];
  row_words_ = (n_ + 63) / 64;
  if (dense_) bits_.assign(n_ * row_words_, 0);
}

void StorageBuilder::add(std::uint32_t caller_i, std::uint32_t caller_j) {
  if (caller_i >= n_ || caller_j >= n_ || caller_i == caller_j)
    throw std::invalid_argument("space syntax: edge (" + std::to_string(caller_i) + ", " + std::to_string(caller_j) +
                                ") is not a pair of distinct nodes among " + std::to_string(n_));
  std::uint32_t i = internal_[caller_i], j = internal_[caller_j];
  if (i > j) std::swap(i, j);
  if (dense_) {
    std::uint64_t& word = bits_[std::size_t{i} * row_words_ + j / 64];
    if (word >> (j % 64) & 1u)
      throw std::invalid_argument("space syntax: the edge (" + std::to_string(caller_i) + ", " +
                                  std::to_string(caller_j) + ") is given twice");
    word |= std::uint64_t{1} << (j % 64);
    bits_[std::size_t{j} * row_words_ + i / 64] |= std::uint64_t{1} << (i % 64);
  } else {
    pairs_.push_back(std::uint64_t{i} << 32 | j);
  }
}

void finish_storage(Storage& g) {
  g.degree.assign(g.n, 0);
  if (g.dense) {
    g.first_word.assign(g.n, 1);
    g.last_word.assign(g.n, 0);
    for (std::size_t i = 0; i < g.n; ++i) {
      const std::uint64_t* r = g.row(i);
      std::uint32_t deg = 0;
      for (std::size_t w = 0; w < g.words; ++w) {
        if (!r[w]) continue;
        if (g.first_word[i] > g.last_word[i]) g.first_word[i] = static_cast<std::uint32_t>(w);
        g.last_word[i] = static_cast<std::uint32_t>(w);
        deg += static_cast<std::uint32_t>(__builtin_popcountll(r[w]));
      }
      g.degree[i] = deg;
    }
  } else {
    for (std::size_t i = 0; i < g.n; ++i) g.degree[i] = static_cast<std::uint32_t>(g.offset[i + 1] - g.offset[i]);
  }
  std::uint64_t twice = 0;
  for (std::uint32_t d : g.degree) twice += d;
  ATTENUVIS_CHECK_EQ(twice % 2, 0u);
  g.m = twice / 2;
}

Storage StorageBuilder::finish() {
  Storage g;
  g.n = n_;
  g.caller = std::move(caller_);
  g.internal = std::move(internal_);
  g.position = std::move(position_);
  g.dense = dense_;
  g.words = row_words_;
  if (dense_) {
    g.bits = std::move(bits_);
  } else {
    // Sorted pairs, duplicates refused (each line of sight comes once).
    std::sort(pairs_.begin(), pairs_.end());
    if (std::adjacent_find(pairs_.begin(), pairs_.end()) != pairs_.end()) {
      const std::uint64_t p = *std::adjacent_find(pairs_.begin(), pairs_.end());
      throw std::invalid_argument("space syntax: the edge (" + std::to_string(g.caller[p >> 32]) + ", " +
                                  std::to_string(g.caller[p & 0xffffffffu]) + ") is given twice");
    }
    std::vector<std::uint32_t> count(n_, 0);
    for (std::uint64_t p : pairs_) ++count[p >> 32], ++count[p & 0xffffffffu];
    g.offset.assign(n_ + 1, 0);
    for (std::size_t i = 0; i < n_; ++i) g.offset[i + 1] = g.offset[i] + count[i];
    g.adjacency.resize(g.offset[n_]);
    std::vector<std::uint64_t> at(g.offset.begin(), g.offset.end() - 1);
    // Pairs sorted by (i, j): row r receives its partners below r while the
    // pairs of those rows go by, then its own partners above r, in order.
    for (std::uint64_t p : pairs_) {
      const std::uint32_t i = static_cast<std::uint32_t>(p >> 32), j = static_cast<std::uint32_t>(p & 0xffffffffu);
      g.adjacency[at[i]++] = j;
      g.adjacency[at[j]++] = i;
    }
    std::vector<std::uint64_t>().swap(pairs_);
  }
  finish_storage(g);
  return g;
}

}  // namespace space_syntax_detail

struct GraphCollector::State {
  space_syntax_detail::StorageBuilder builder;
  State(const std::vector<Eigen::Vector3d>& eyes, bool dense) : builder(eyes, dense) {}
};

GraphCollector::GraphCollector(const std::vector<Eigen::Vector3d>& eyes, bool bit_rows)
    : state_(std::make_unique<State>(eyes, bit_rows)) {}
GraphCollector::~GraphCollector() = default;

void GraphCollector::add(const std::vector<Edge>& block) {
  for (const Edge& e : block) state_->builder.add(e.i, e.j);
}

std::function<void(const std::vector<Edge>&)> GraphCollector::sink() {
  return [this](const std::vector<Edge>& block) { add(block); };
}

VisibilityGraph GraphCollector::finish(const SpaceSyntaxShare& share) {
  space_syntax_detail::StorageBuilder& b = state_->builder;
  if (share.count > 1) {
    // Each share saw only its own pairs: join them (an OR of bit rows, or
    // every process's pairs in process order; CSR sorts them anyway).
    if (b.dense() && share.or_words) share.or_words(b.words());
    else if (!b.dense() && share.gather) share.gather(b.words());
    else throw std::invalid_argument("space syntax: a graph in several shares needs a join step");
  }
  auto storage = std::make_shared<VisibilityGraph::Storage>(b.finish());
  return VisibilityGraph(std::move(storage));
}

}  // namespace attenuvis::visgraph
