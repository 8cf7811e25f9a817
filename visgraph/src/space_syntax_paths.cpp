// Metric shortest paths and through vision (space_syntax_measures.hpp).
#include "space_syntax_measures.hpp"

#include <attenuvis/io/check.hpp>

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace attenuvis::visgraph::space_syntax_detail {

namespace {

// Per-thread Dijkstra state.  A node i sees is closed from the start at
// l = d_ij: no path is shorter than the straight line (triangle
// inequality), so relaxations skip it; a node popped from the heap is closed
// too.  Ties in the heap go by node index: the same order, hence the same
// rounding of the sums, in every run.
struct Dijkstra {
  explicit Dijkstra(std::size_t n) : length(n), closed((n + 63) / 64) {}
  std::vector<double> length;
  std::vector<std::uint64_t> closed;
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;

  bool is_closed(std::uint32_t v) const { return closed[v / 64] >> (v % 64) & 1u; }
  void close(std::uint32_t v) { closed[v / 64] |= std::uint64_t{1} << (v % 64); }

  // Candidates of u's row that are still open, in increasing index.
  template <class F>
  void open_neighbours(const Storage& g, std::uint32_t u, F&& f) const {
    if (g.dense) {
      if (g.first_word[u] > g.last_word[u]) return;
      const std::uint64_t* r = g.row(u);
      for (std::size_t w = g.first_word[u]; w <= g.last_word[u]; ++w)
        for (std::uint64_t x = r[w] & ~closed[w]; x; x &= x - 1) f(static_cast<std::uint32_t>(w * 64 + lowest_bit(x)));
    } else {
      for_each_neighbour(g, u, [&](std::uint32_t v) {
        if (!is_closed(v)) f(v);
      });
    }
  }

  void run(const Storage& g, std::uint32_t s) {
    std::fill(length.begin(), length.end(), std::numeric_limits<double>::infinity());
    std::fill(closed.begin(), closed.end(), 0);
    length[s] = 0;
    close(s);
    for_each_neighbour(g, s, [&](std::uint32_t v) {
      length[v] = g.distance(s, v);
      close(v);
      heap.push({length[v], v});
    });
    while (!heap.empty()) {
      const double l = heap.top().first;
      const std::uint32_t u = heap.top().second;
      heap.pop();
      if (l > length[u]) continue;  // a stale entry
      close(u);
      open_neighbours(g, u, [&](std::uint32_t v) {
        const double candidate = l + g.distance(u, v);
        if (candidate < length[v]) length[v] = candidate, heap.push({candidate, v});
      });
    }
  }
};

// Floor division for the cell walk (b > 0).
std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The nodes' cells on the square grid of spacing h: cell (cx, cy) of each
// node, and the nodes of each cell as a linked list through `next` (several
// where levels stack), the head of each cell in a dense array over the
// nodes' bounding box.
struct PlanGrid {
  std::vector<std::int64_t> cx, cy;
  std::int64_t nx = 0, ny = 0;
  std::vector<std::int32_t> head;  // per cell: first node, -1 for none
  std::vector<std::int32_t> next;  // per node: next node of its cell, -1 for none
  std::int32_t first(std::int64_t x, std::int64_t y) const {
    return x < 0 || y < 0 || x >= nx || y >= ny ? -1 : head[static_cast<std::size_t>(y * nx + x)];
  }
};

// More cells than this (2 GiB of heads) are refused.
constexpr double kMaxPlanCells = 5.0e8;

PlanGrid plan_grid(const Storage& g, double h) {
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("through vision: needs the spacing of the node grid, whose cells it walks");
  PlanGrid p;
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  for (const auto& e : g.position) x0 = std::min(x0, e.x()), y0 = std::min(y0, e.y());
  p.cx.resize(g.n);
  p.cy.resize(g.n);
  for (std::size_t i = 0; i < g.n; ++i) {
    const double fx = (g.position[i].x() - x0) / h, fy = (g.position[i].y() - y0) / h;
    if (!(fx < 4e9 && fy < 4e9))
      throw std::invalid_argument("through vision: the nodes span more than 4e9 cells of " + std::to_string(h) + " m");
    p.cx[i] = std::llround(fx);
    p.cy[i] = std::llround(fy);
    if (std::abs(fx - p.cx[i]) > 1e-6 || std::abs(fy - p.cy[i]) > 1e-6)
      throw std::invalid_argument("through vision: node " + std::to_string(g.caller[i]) + " is not on a square grid of spacing " +
                                  std::to_string(h) + " m (through vision walks the grid's cells)");
    p.nx = std::max(p.nx, p.cx[i] + 1);
    p.ny = std::max(p.ny, p.cy[i] + 1);
  }
  if (static_cast<double>(p.nx) * static_cast<double>(p.ny) > kMaxPlanCells)
    throw std::invalid_argument("through vision: the nodes span " + std::to_string(p.nx) + " x " + std::to_string(p.ny) +
                                " cells of " + std::to_string(h) + " m, more than 5e8");
  p.head.assign(static_cast<std::size_t>(p.nx * p.ny), -1);
  p.next.assign(g.n, -1);
  for (std::size_t i = g.n; i-- > 0;) {
    std::int32_t& h0 = p.head[static_cast<std::size_t>(p.cy[i] * p.nx + p.cx[i])];
    p.next[i] = h0;
    h0 = static_cast<std::int32_t>(i);
  }
  return p;
}

// The cells strictly between a and b along depthmapX's line walk
// (space_syntax.hpp): visit(x, y) for each.
template <class Visit>
void walk_cells(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, Visit&& visit) {
  const std::int64_t dx = bx - ax, dy = by - ay;
  const std::int64_t t = std::max(std::llabs(dx), std::llabs(dy));
  if (t <= 1) return;
  const std::int64_t sx = dx > 0 ? 1 : dx < 0 ? -1 : 0, sy = dy > 0 ? 1 : dy < 0 ? -1 : 0;
  if (std::llabs(dx) == std::llabs(dy)) {
    for (std::int64_t s = 1; s < t; ++s) visit(ax + s * sx, ay + s * sy);
    return;
  }
  const bool x_major = std::llabs(dx) > std::llabs(dy);
  // Minor coordinate at step s, times 2t: (2 a + 1) t + 2 s d (the centre of
  // cell a is a + 1/2); on a cell boundary when divisible by 2t.
  const std::int64_t a_minor = x_major ? ay : ax, d_minor = x_major ? dy : dx;
  for (std::int64_t s = 1; s < t; ++s) {
    const std::int64_t major = (x_major ? ax : ay) + s * (x_major ? sx : sy);
    const std::int64_t twice = (2 * a_minor + 1) * t + 2 * s * d_minor;
    const std::int64_t cell = floor_div(twice, 2 * t);
    const bool boundary = twice - cell * 2 * t == 0;
    const auto emit = [&](std::int64_t minor) { x_major ? visit(major, minor) : visit(minor, major); };
    emit(cell);
    if (boundary) emit(cell - 1);
  }
}
}  // namespace

void shortest_paths(const Storage& g, const Owned& owned, int threads,
                    const std::function<void(std::size_t, const std::vector<double>&)>& visit) {
  tbb::enumerable_thread_specific<Dijkstra> state([&] { return Dijkstra(g.n); });
  for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
    Dijkstra& d = state.local();
    for (std::size_t s = begin; s < end; ++s) {
      d.run(g, static_cast<std::uint32_t>(s));
      visit(s, d.length);
    }
  });
}

ThroughVision through_vision(const Storage& g, double spacing, const std::vector<double>& sigmas, double eps,
                             const Owned& owned, int threads) {
  const PlanGrid grid = plan_grid(g, spacing);
  const std::size_t K = sigmas.size();
  // A node's fixed-point sum stays below 2^63 while lines x 2^32 does.
  if (g.m >= (std::uint64_t{1} << 31))
    throw std::invalid_argument("through vision: " + std::to_string(g.m) + " lines of sight, more than 2^31");
  struct Sums {
    std::vector<std::int64_t> counts, weighted;  // [k * n + node]
  };
  tbb::enumerable_thread_specific<Sums> local([&] {
    return Sums{std::vector<std::int64_t>(K * g.n, 0), std::vector<std::int64_t>(K * g.n, 0)};
  });
  std::vector<Threshold> threshold;
  for (double sigma : sigmas) threshold.emplace_back(sigma, eps);
  for_owned_blocks(g.n, owned, threads, [&](std::size_t begin, std::size_t end) {
    Sums& sums = local.local();
    std::vector<std::int64_t> in(K), weight(K);
    for (std::size_t i = begin; i < end; ++i)
      for_each_neighbour(g, i, [&](std::uint32_t j) {
        if (j < i) return;
        const double d = g.distance(i, j);
        bool any = false;
        for (std::size_t k = 0; k < K; ++k) {
          in[k] = threshold[k].keeps(d);
          weight[k] = in[k] ? std::llround(std::exp(-sigmas[k] * d) * kThroughVisionScale) : 0;
          any = any || in[k];
        }
        if (!any) return;
        walk_cells(grid.cx[i], grid.cy[i], grid.cx[j], grid.cy[j], [&](std::int64_t x, std::int64_t y) {
          for (std::int32_t v = grid.first(x, y); v >= 0; v = grid.next[static_cast<std::size_t>(v)])
            for (std::size_t k = 0; k < K; ++k) {
              sums.counts[k * g.n + static_cast<std::size_t>(v)] += in[k];
              sums.weighted[k * g.n + static_cast<std::size_t>(v)] += weight[k];
            }
        });
      });
  });
  ThroughVision out;
  out.counts.assign(K, std::vector<std::int64_t>(g.n, 0));
  out.weighted = out.counts;
  for (const Sums& s : local)
    for (std::size_t k = 0; k < K; ++k)
      for (std::size_t v = 0; v < g.n; ++v) {
        out.counts[k][v] += s.counts[k * g.n + v];
        out.weighted[k][v] += s.weighted[k * g.n + v];
      }
  return out;
}

}  // namespace attenuvis::visgraph::space_syntax_detail
