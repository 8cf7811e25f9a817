// The space-syntax measures (visgraph/space_syntax.hpp): values worked by
// hand on small graphs, the bit-parallel BFS against one queue BFS per node
// written here, bit rows against CSR, and shares of several processes (run
// on threads, joined through an in-process exchange as MPI joins them)
// against one process, bit for bit.  The comparison with networkx on random
// graphs and scenes is python/tests/test_space_syntax.py.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>
#include <attenuvis/visgraph/space_syntax.hpp>

#include <catch2/catch.hpp>

#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <random>
#include <thread>

namespace vg = attenuvis::visgraph;
using Eigen::Vector3d;

namespace {

vg::SpaceSyntaxOptions options(const std::string& measures, std::vector<double> sigmas = {0.0}, double eps = 0.0,
                               int radius = 0) {
  vg::SpaceSyntaxOptions o;
  o.sigmas = std::move(sigmas);
  o.measures = vg::parse_measures(measures);
  o.contrast_threshold = eps;
  o.radius = radius;
  return o;
}

vg::SpaceSyntaxResult on_edges(const std::vector<Vector3d>& eyes, const std::vector<vg::Edge>& edges,
                               const vg::SpaceSyntaxOptions& o, bool bit_rows) {
  vg::GraphCollector collector(eyes, bit_rows);
  collector.add(edges);
  return vg::space_syntax(collector.finish(), o);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void require_identical(const vg::SpaceSyntaxResult& a, const vg::SpaceSyntaxResult& b) {
  REQUIRE(a.columns.size() == b.columns.size());
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    INFO(a.columns[c].measure << " condition " << a.columns[c].condition);
    CHECK(a.columns[c].measure == b.columns[c].measure);
    CHECK(same_bits(a.columns[c].values, b.columns[c].values));
  }
  CHECK(a.edges == b.edges);
  CHECK(a.components == b.components);
}

// n nodes scattered over a 40 m square (on a 1 m grid, some stacked), an
// edge with probability p, and a few nodes left alone.
void random_graph(unsigned seed, std::size_t n, double p, std::vector<Vector3d>& eyes, std::vector<vg::Edge>& edges) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cell(0, 39);
  std::uniform_real_distribution<double> u(0, 1);
  eyes.clear();
  edges.clear();
  for (std::size_t i = 0; i < n; ++i) eyes.push_back({cell(rng) + 0.5, cell(rng) + 0.5, 3 * u(rng)});
  for (std::uint32_t i = 0; i + 5 < n; ++i)
    for (std::uint32_t j = i + 1; j + 5 < n; ++j)
      if (u(rng) < p) edges.push_back({i, j, 0.0});
}

// Node count and total depth from each origin by one queue BFS each.
void plain_depths(std::size_t n, const std::vector<vg::Edge>& edges, int radius, std::vector<double>& count,
                  std::vector<double>& mean_depth) {
  std::vector<std::vector<std::uint32_t>> next(n);
  for (const vg::Edge& e : edges) next[e.i].push_back(e.j), next[e.j].push_back(e.i);
  count.assign(n, 0);
  mean_depth.assign(n, -1);
  for (std::size_t s = 0; s < n; ++s) {
    std::vector<int> depth(n, -1);
    std::vector<std::uint32_t> queue = {static_cast<std::uint32_t>(s)};
    depth[s] = 0;
    double total = 0;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::uint32_t v = queue[head];
      if (radius > 0 && depth[v] == radius) continue;
      for (std::uint32_t u : next[v])
        if (depth[u] < 0) depth[u] = depth[v] + 1, total += depth[u], queue.push_back(u);
    }
    count[s] = static_cast<double>(queue.size());
    if (queue.size() > 1) mean_depth[s] = total / (queue.size() - 1.0);
  }
}
}  // namespace

TEST_CASE("space syntax: a path of five nodes, worked by hand", "[visgraph][space_syntax]") {
  // 0 - 1 - 2 - 3 - 4, 1 m apart on x.
  std::vector<Vector3d> eyes;
  for (int i = 0; i < 5; ++i) eyes.push_back({double(i), 0, 0});
  std::vector<vg::Edge> edges;
  for (std::uint32_t i = 0; i < 4; ++i) edges.push_back({i, i + 1, 1.0});
  const vg::SpaceSyntaxResult r =
      on_edges(eyes, edges, options("connectivity,clustering,control,controllability,mean-depth,integration,entropy"), true);
  // Centre node 2: depths 1, 1, 2, 2 -> TD = 6, n = 5, MD = 6/4 = 1.5.
  CHECK(r.values("mean_depth", 0)[2] == 1.5);
  CHECK(r.values("node_count", 0)[2] == 5);
  // RA = 2 (1.5 - 1) / 3 = 1/3; D_5 = 2 (5 (log2(7/3) - 1) + 1) / 12 = 0.3519936844
  // (log2(7/3) = 1.2223924213); integration [HH] = D_5 / RA = 1.0559810533.
  CHECK(r.values("integration_hh", 0)[2] == Approx(1.0559810533).epsilon(1e-9));
  // [Tekl] = ln(3/2) / ln(6 - 5 + 1) = 0.4054651081 / 0.6931471806 = 0.5849625007.
  CHECK(r.values("integration_tekl", 0)[2] == Approx(0.5849625007).epsilon(1e-9));
  // Entropy: p_1 = p_2 = 1/2 -> 1 bit.
  CHECK(r.values("entropy", 0)[2] == 1.0);
  // Control of node 1: 1/k_0 + 1/k_2 = 1 + 1/2; of node 0 (one neighbour): -1 as depthmapX writes.
  CHECK(r.values("control", 0)[1] == 1.5);
  CHECK(r.values("control", 0)[0] == -1.0);
  // Controllability of node 2: k = 2 over |N(1) u N(3)| = |{0, 2, 4}| = 3.
  CHECK(r.values("controllability", 0)[2] == Approx(2.0 / 3.0).epsilon(1e-15));
  CHECK(r.values("clustering", 0)[2] == 0.0);
  CHECK(r.values("point_first_moment", 0)[2] == 2.0);
  // End node 0: depths 1, 2, 3, 4 -> MD = 10/4.
  CHECK(r.values("mean_depth", 0)[0] == 2.5);
}

TEST_CASE("space syntax: through vision walks depthmapX's cells", "[visgraph][space_syntax]") {
  // Cells (0,0) .. (2,1) at 1 m; one line from cell (0,0) to cell (2,1):
  // its midpoint (1.5, 1.0) lies on the boundary between rows 0 and 1, so
  // both cells (1,0) and (1,1) count it, and no other cell does.
  std::vector<Vector3d> eyes;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) eyes.push_back({x + 0.5, y + 0.5, 1.7});
  const std::vector<vg::Edge> edges = {{0, 5, 0.0}};
  vg::SpaceSyntaxOptions o = options("through-vision", {0.1});
  o.grid_spacing = 1.0;
  const vg::SpaceSyntaxResult tie = on_edges(eyes, edges, o, true);
  CHECK(tie.values("through_vision", 0) == std::vector<double>{0, 1, 0, 0, 1, 0});
  // A straight line over three cells counts at the middle one only.
  const vg::SpaceSyntaxResult row = on_edges(eyes, {{0, 2, 0.0}}, o, true);
  CHECK(row.values("through_vision", 0) == std::vector<double>{0, 1, 0, 0, 0, 0});
}

TEST_CASE("space syntax: the bit-parallel BFS equals one BFS per node", "[visgraph][space_syntax]") {
  // 700 nodes: a full sweep of 512 origins and a partial one; sparse and
  // dense graphs, disconnected parts and isolated nodes, every radius, both
  // storages (the sweep reads bit rows and neighbour lists by different code).
  for (double p : {0.004, 0.05, 0.6}) {
    std::vector<Vector3d> eyes;
    std::vector<vg::Edge> edges;
    random_graph(7, 700, p, eyes, edges);
    for (int radius : {0, 1, 2, 3}) {
      std::vector<double> count, md;
      plain_depths(eyes.size(), edges, radius, count, md);
      const std::string suffix = radius > 0 ? "_r" + std::to_string(radius) : "";
      for (bool bit_rows : {true, false}) {
        INFO("p = " << p << ", radius " << radius << (bit_rows ? ", bit rows" : ", CSR"));
        const vg::SpaceSyntaxResult r = on_edges(eyes, edges, options("mean-depth", {0.0}, 0.0, radius), bit_rows);
        CHECK(r.values("node_count" + suffix, 0) == count);
        CHECK(r.values("mean_depth" + suffix, 0) == md);
      }
    }
  }
}

TEST_CASE("space syntax: bit rows and CSR give the same bits", "[visgraph][space_syntax]") {
  std::vector<Vector3d> eyes;
  std::vector<vg::Edge> edges;
  random_graph(11, 300, 0.08, eyes, edges);
  vg::SpaceSyntaxOptions o = options("all", {0.0, 0.02, 0.3}, 0.02, 0);
  o.measures.add(vg::Measure::step_depth);
  o.depth_origins = {3, 200};
  o.grid_spacing = 1.0;
  require_identical(on_edges(eyes, edges, o, true), on_edges(eyes, edges, o, false));
  o.radius = 2;
  require_identical(on_edges(eyes, edges, o, true), on_edges(eyes, edges, o, false));
}

TEST_CASE("space syntax: refuses what it cannot compute", "[visgraph][space_syntax]") {
  std::vector<Vector3d> eyes;
  std::vector<vg::Edge> edges;
  random_graph(3, 50, 0.2, eyes, edges);
  CHECK_THROWS_WITH(vg::parse_measures("integration,integraton"), Catch::Contains("unknown measure 'integraton'"));
  CHECK_THROWS_WITH(vg::parse_measures("control,control"), Catch::Contains("given twice"));
  CHECK_THROWS_WITH(on_edges(eyes, edges, options("through-vision"), true), Catch::Contains("spacing"));
  CHECK_THROWS_WITH(on_edges(eyes, edges, options("connectivity", {-1.0}), true), Catch::Contains("sigma"));
  CHECK_THROWS_WITH(on_edges(eyes, edges, options("connectivity", {0.0}, 1.0), true), Catch::Contains("threshold"));
  std::vector<vg::Edge> twice = edges;
  twice.push_back(edges.front());
  CHECK_THROWS_WITH(on_edges(eyes, twice, options("connectivity"), true), Catch::Contains("given twice"));
  CHECK_THROWS_WITH(on_edges(eyes, twice, options("connectivity"), false), Catch::Contains("given twice"));
  CHECK_THROWS_WITH(on_edges(eyes, {{0, 0, 0.0}}, options("connectivity"), true), Catch::Contains("distinct"));
  vg::SpaceSyntaxOptions o = options("step-depth");
  o.depth_origins = {500};
  CHECK_THROWS_WITH(on_edges(eyes, edges, o, true), Catch::Contains("origin 500"));
  // The estimate refuses a graph larger than the memory it is given.
  const vg::SpaceSyntaxEstimate e = vg::estimate_space_syntax(200000, 2e10, options("all"));
  CHECK(e.bit_rows);
  CHECK_THAT(vg::space_syntax_refusal(e, 1e9, 200000), Catch::Contains("coarser --spacing"));
  CHECK(vg::space_syntax_refusal(e, 1e12, 200000).empty());
}

namespace {
// Sums and joins over `count` participants, each calling from its own thread.
class Exchange {
 public:
  explicit Exchange(int count) : count_(count) {}
  template <class T, class Join>
  void all(std::vector<T>& v, int index, Join join) {
    std::unique_lock<std::mutex> lock(mutex_);
    const std::uint64_t round = round_;
    parts_.resize(static_cast<std::size_t>(count_));
    auto& mine = parts_[static_cast<std::size_t>(index)];
    mine.assign(reinterpret_cast<const char*>(v.data()), reinterpret_cast<const char*>(v.data() + v.size()));
    if (++arrived_ == count_) {
      arrived_ = 0;
      ++round_;
      done_.notify_all();
    } else {
      done_.wait(lock, [&] { return round_ != round; });
    }
    std::vector<std::vector<T>> all(static_cast<std::size_t>(count_));
    for (int s = 0; s < count_; ++s) {
      const std::string& bytes = parts_[static_cast<std::size_t>(s)];
      all[static_cast<std::size_t>(s)].resize(bytes.size() / sizeof(T));
      if (!bytes.empty()) std::memcpy(all[static_cast<std::size_t>(s)].data(), bytes.data(), bytes.size());
    }
    join(all, v);
    // Everyone must have read the parts before the next round writes them.
    if (++left_ == count_) {
      left_ = 0;
      ++leave_round_;
      done_.notify_all();
    } else {
      const std::uint64_t leave = leave_round_;
      done_.wait(lock, [&] { return leave_round_ != leave; });
    }
  }

 private:
  int count_, arrived_ = 0, left_ = 0;
  std::uint64_t round_ = 0, leave_round_ = 0;
  std::vector<std::string> parts_;
  std::mutex mutex_;
  std::condition_variable done_;
};

template <class T>
void add_all(const std::vector<std::vector<T>>& parts, std::vector<T>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    T total = T(0);
    for (const auto& p : parts) total += p[i];
    v[i] = total;
  }
}
}  // namespace

TEST_CASE("space syntax: shares of several processes equal one process, bit for bit", "[visgraph][space_syntax]") {
  // A 3 m grid (about 270 nodes): every measure, both storages, 2 and 3
  // shares; under the sanitizers a finer grid costs a minute for nothing more.
  const vg::Scene scene(vg::classic_layout(2));
  vg::NodeGridOptions grid;
  grid.spacing = 3.0;
  grid.walkable = vg::classic_layout_walkable_groups();
  const std::vector<Vector3d> eyes = vg::generate_nodes(scene, grid).eyes;
  vg::VisibilityOptions pass;
  pass.sigmas = {1.5e-4, 0.0287};
  vg::SpaceSyntaxOptions o = options("all", pass.sigmas, 0.5);
  o.grid_spacing = 3.0;
  for (vg::GraphStorage storage : {vg::GraphStorage::bit_rows, vg::GraphStorage::csr}) {
    o.storage = storage;
    const vg::SpaceSyntaxRun one = vg::space_syntax(scene, eyes, pass, o);
    for (int count : {2, 3}) {
      INFO(count << " shares, " << (storage == vg::GraphStorage::csr ? "CSR" : "bit rows"));
      Exchange exchange(count);
      std::vector<vg::SpaceSyntaxResult> shares(static_cast<std::size_t>(count));
      std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
      std::vector<std::thread> threads;
      for (int s = 0; s < count; ++s)
        threads.emplace_back([&, s] {
          vg::VisibilityOptions p = pass;
          p.threads = 1;
          p.share.index = s;
          p.share.count = count;
          p.share.combine = [&](std::vector<std::int64_t>& sums, std::vector<double>& maxima) {
            exchange.all(sums, s, add_all<std::int64_t>);
            exchange.all(maxima, s, [](const std::vector<std::vector<double>>& parts, std::vector<double>& v) {
              for (std::size_t i = 0; i < v.size(); ++i)
                for (const auto& q : parts) v[i] = std::max(v[i], q[i]);
            });
          };
          vg::SpaceSyntaxOptions so = o;
          so.threads = 1;
          so.share.index = s;
          so.share.count = count;
          so.share.or_words = [&](std::vector<std::uint64_t>& v) {
            exchange.all(v, s, [](const std::vector<std::vector<std::uint64_t>>& parts, std::vector<std::uint64_t>& w) {
              for (std::size_t i = 0; i < w.size(); ++i)
                for (const auto& q : parts) w[i] |= q[i];
            });
          };
          so.share.gather = [&](std::vector<std::uint64_t>& v) {
            exchange.all(v, s, [](const std::vector<std::vector<std::uint64_t>>& parts, std::vector<std::uint64_t>& w) {
              w.clear();
              for (const auto& q : parts) w.insert(w.end(), q.begin(), q.end());
            });
          };
          so.share.sum = [&](std::vector<double>& v) { exchange.all(v, s, add_all<double>); };
          so.share.sum_integers = [&](std::vector<std::int64_t>& v) { exchange.all(v, s, add_all<std::int64_t>); };
          try {
            shares[static_cast<std::size_t>(s)] = vg::space_syntax(scene, eyes, p, so).measures;
          } catch (...) {
            errors[static_cast<std::size_t>(s)] = std::current_exception();
          }
        });
      for (std::thread& t : threads) t.join();
      for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
      for (const vg::SpaceSyntaxResult& r : shares) require_identical(r, one.measures);
    }
  }
}
