// Bit-parallel multi-source BFS and plain BFS (space_syntax_depth.hpp).
#include "space_syntax_depth.hpp"

#include <attenuvis/io/check.hpp>

#include <algorithm>
#include <deque>

namespace attenuvis::visgraph::space_syntax_detail {

namespace {
constexpr std::size_t W = kSweepWords;

// The word loops below are written for 8 lanes of 64 bits; GCC builds them
// for AVX-512 and AVX2 as well and picks one when the program starts.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ATTENUVIS_SWEEP_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_SWEEP_CLONES
#endif
}  // namespace

DepthSweeper::DepthSweeper(const Storage& g)
    : g_(g), seen_(g.n * W, 0), frontier_(g.n * W, 0), next_(g.n * W, 0), active_((g.n + 63) / 64, 0) {}

// The origin bits of node v OR-ed into t (8 words).
inline void merge(std::uint64_t* t, const std::uint64_t* f) {
  for (std::size_t w = 0; w < W; ++w) t[w] |= f[w];
}

// Top-down: every frontier node ORs its origin bits into its neighbours.
// Returns the frontier nodes.  The neighbour loops are written out here
// (not through for_each_neighbour) so that each clone compiles them for its
// instruction set.
ATTENUVIS_SWEEP_CLONES std::uint64_t DepthSweeper::push() {
  std::fill(next_.begin(), next_.end(), 0);
  std::uint64_t read = 0;
  std::uint64_t* next = next_.data();
  for (std::size_t a = 0; a < active_.size(); ++a)
    for (std::uint64_t bits = active_[a]; bits; bits &= bits - 1) {
      const std::size_t v = a * 64 + lowest_bit(bits);
      const std::uint64_t* f = frontier_.data() + v * W;
      ++read;
      if (g_.dense) {
        if (g_.first_word[v] > g_.last_word[v]) continue;
        const std::uint64_t* r = g_.row(v);
        for (std::size_t w = g_.first_word[v]; w <= g_.last_word[v]; ++w)
          for (std::uint64_t x = r[w]; x; x &= x - 1) merge(next + (w * 64 + lowest_bit(x)) * W, f);
      } else {
        for (std::uint64_t p = g_.offset[v]; p < g_.offset[v + 1]; ++p) merge(next + std::size_t{g_.adjacency[p]} * W, f);
      }
    }
  return read;
}

// Bottom-up: every node still missing some origin ORs the frontier bits of
// its neighbours on the frontier, stopping once it has every missing one
// (checked every eighth merge: the check costs as much as a merge).
// Returns the work in merges: those done, and in neighbour lists an eighth
// of the entries passed over (4 sequential bytes against 64 random ones).
ATTENUVIS_SWEEP_CLONES std::uint64_t DepthSweeper::pull() {
  const std::uint64_t* frontier = frontier_.data();
  const std::uint64_t* active = active_.data();
  std::uint64_t read = 0;
  for (std::size_t u = 0; u < g_.n; ++u) {
    const std::uint64_t* s = seen_.data() + u * W;
    // The bits gather in a local array (registers: one vector of eight
    // words), not in next_, which the compiler must assume aliases the
    // frontier and would store to after every merge.
    std::uint64_t missing[W], got[W] = {};
    std::uint64_t open = 0;
    for (std::size_t w = 0; w < W; ++w) missing[w] = ~s[w] & valid_[w], open |= missing[w];
    const auto complete = [&] {
      std::uint64_t still = 0;
      for (std::size_t w = 0; w < W; ++w) still |= missing[w] & ~got[w];
      return still == 0;
    };
    unsigned since_check = 0;
    if (!open || (g_.dense && g_.first_word[u] > g_.last_word[u])) {
      // reached by every origin, or no neighbours: nothing to gather
    } else if (g_.dense) {
      const std::uint64_t* r = g_.row(u);
      for (std::size_t w = g_.first_word[u]; w <= g_.last_word[u]; ++w) {
        const std::uint64_t on = r[w] & active[w];
        for (std::uint64_t x = on; x; x &= x - 1) merge(got, frontier + (w * 64 + lowest_bit(x)) * W);
        const auto merged = static_cast<unsigned>(__builtin_popcountll(on));
        since_check += merged;
        read += merged;
        if (since_check >= 8) {
          since_check = 0;
          if (complete()) break;
        }
      }
    } else {
      std::uint64_t p = g_.offset[u];
      for (; p < g_.offset[u + 1]; ++p) {
        const std::uint32_t v = g_.adjacency[p];
        if (!(active[v / 64] >> (v % 64) & 1)) continue;
        merge(got, frontier + std::size_t{v} * W);
        ++read;
        if (++since_check == 8) {
          since_check = 0;
          if (complete()) break;
        }
      }
      read += (p - g_.offset[u]) / 8;
    }
    std::copy(got, got + W, next_.data() + u * W);
  }
  return read;
}

bool DepthSweeper::settle(std::size_t d, SweepDepths& out, std::uint64_t& push_work, std::uint64_t& pull_work) {
  out.counts.resize((d + 1) * kSweepOrigins, 0);
  std::uint32_t* count = out.counts.data() + d * kSweepOrigins;
  bool reached = false;
  push_work = pull_work = 0;
  std::fill(active_.begin(), active_.end(), 0);
  for (std::size_t u = 0; u < g_.n; ++u) {
    std::uint64_t* t = next_.data() + u * W;
    std::uint64_t* s = seen_.data() + u * W;
    std::uint64_t* f = frontier_.data() + u * W;
    std::uint64_t fresh_any = 0, open = 0;
    for (std::size_t w = 0; w < W; ++w) {
      const std::uint64_t fresh = t[w] & ~s[w];
      f[w] = fresh;
      s[w] |= fresh;
      fresh_any |= fresh;
      open |= ~s[w] & valid_[w];
      for (std::uint64_t x = fresh; x; x &= x - 1) ++count[w * 64 + lowest_bit(x)];
    }
    if (fresh_any) reached = true, push_work += g_.degree[u], active_[u / 64] |= std::uint64_t{1} << (u % 64);
    if (open) pull_work += g_.degree[u];
  }
  out.levels = d + 1;
  return reached;
}

void DepthSweeper::run(std::size_t first, std::size_t origins, int max_depth, SweepDepths& out) {
  ATTENUVIS_CHECK_LE(origins, kSweepOrigins);
  ATTENUVIS_CHECK_LE(first + origins, g_.n);
  std::fill(seen_.begin(), seen_.end(), 0);
  std::fill(frontier_.begin(), frontier_.end(), 0);
  std::fill(active_.begin(), active_.end(), 0);
  for (std::size_t w = 0; w < W; ++w) {
    const std::size_t lo = w * 64;
    valid_[w] = origins >= lo + 64 ? ~std::uint64_t{0} : origins > lo ? (std::uint64_t{1} << (origins - lo)) - 1 : 0;
  }
  out.first = first;
  out.origins = origins;
  out.counts.assign(kSweepOrigins, 0);
  out.levels = 1;
  std::uint64_t push_work = 0, pull_work = 0;
  for (std::size_t b = 0; b < origins; ++b) {
    const std::size_t v = first + b;
    seen_[v * W + b / 64] |= std::uint64_t{1} << (b % 64);
    frontier_[v * W + b / 64] |= std::uint64_t{1} << (b % 64);
    active_[v / 64] |= std::uint64_t{1} << (v % 64);
    out.counts[b] = 1;
    push_work += g_.degree[v];
  }
  for (std::size_t v = 0; v < g_.n; ++v) pull_work += g_.degree[v];
  // Push reads every frontier node's list whole; pull reads at most the
  // lists of the nodes still open, and stops early in each once it has
  // found all that node's missing origins, which happens often in dense
  // graphs and rarely in sparse ones.  The share of the open lists that the
  // last pull read predicts the next one's cost.
  double pull_share = 0.25;
  for (std::size_t d = 1; max_depth <= 0 || d <= static_cast<std::size_t>(max_depth); ++d) {
    if (pull_share * static_cast<double>(pull_work) < static_cast<double>(push_work)) {
      const std::uint64_t read = pull();
      pull_share = pull_work ? std::max(0.01, static_cast<double>(read) / static_cast<double>(pull_work)) : 0.25;
    } else {
      push();
    }
    if (!settle(d, out, push_work, pull_work)) {
      out.levels = d;  // the last level reached nothing
      out.counts.resize(d * kSweepOrigins);
      break;
    }
  }
}

std::vector<int> step_depths(const Storage& g, const std::vector<std::uint32_t>& origins) {
  std::vector<int> depth(g.n, -1);
  std::vector<std::uint32_t> level, next;
  for (std::uint32_t o : origins)
    if (depth[o] < 0) depth[o] = 0, level.push_back(o);
  for (int d = 1; !level.empty(); ++d) {
    next.clear();
    for (std::uint32_t v : level)
      for_each_neighbour(g, v, [&](std::uint32_t u) {
        if (depth[u] < 0) depth[u] = d, next.push_back(u);
      });
    level.swap(next);
  }
  return depth;
}

std::vector<std::uint32_t> component_sizes(const Storage& g, std::size_t* components) {
  std::vector<std::uint32_t> label(g.n, UINT32_MAX), size;
  std::vector<std::uint32_t> stack;
  for (std::size_t s = 0; s < g.n; ++s) {
    if (label[s] != UINT32_MAX) continue;
    const auto c = static_cast<std::uint32_t>(size.size());
    std::uint32_t members = 1;
    label[s] = c;
    stack.assign(1, static_cast<std::uint32_t>(s));
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      for_each_neighbour(g, v, [&](std::uint32_t u) {
        if (label[u] == UINT32_MAX) label[u] = c, ++members, stack.push_back(u);
      });
    }
    size.push_back(members);
  }
  if (components) *components = size.size();
  std::vector<std::uint32_t> out(g.n);
  for (std::size_t v = 0; v < g.n; ++v) out[v] = size[label[v]];
  return out;
}

}  // namespace attenuvis::visgraph::space_syntax_detail
