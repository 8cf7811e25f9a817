// A pass split into shares (PassShare) gives the one-process results bit for
// bit: degree, the fixed-point S_S sums, distance statistics, pruned counts
// and pair counters, for 2, 3 and 5 shares, on every path of the pass
// (culled and cast all-to-all, pruning, a distance limit, to targets).  The
// shares run here on threads of one process and combine through a shared
// exchange, as MPI's Allreduce combines them across processes in the CLI.
#include "test_visibility_scenes.hpp"

#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vg = attenuvis::visgraph;
using namespace vgtest;

namespace {
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Element-wise sum and maximum over `count` participants, each calling
// combine once from its own thread; all of them receive the totals.
class Exchange {
 public:
  explicit Exchange(int count) : count_(count) {}
  void combine(std::vector<std::int64_t>& sums, std::vector<double>& maxima) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (arrived_ == 0) {
      sums_.assign(sums.size(), 0);
      maxima_.assign(maxima.size(), 0.0);
    }
    mismatch_ = mismatch_ || sums.size() != sums_.size() || maxima.size() != maxima_.size();
    if (mismatch_) throw std::logic_error("the shares' accumulators differ in layout");
    for (std::size_t i = 0; i < sums.size(); ++i) sums_[i] += sums[i];
    for (std::size_t i = 0; i < maxima.size(); ++i) maxima_[i] = std::max(maxima_[i], maxima[i]);
    if (++arrived_ == count_) done_.notify_all();
    done_.wait(lock, [this] { return arrived_ == count_; });
    sums = sums_;
    maxima = maxima_;
  }
  bool mismatch() const { return mismatch_; }  // every share must have the same layout

 private:
  int count_, arrived_ = 0;
  bool mismatch_ = false;
  std::mutex mutex_;
  std::condition_variable done_;
  std::vector<std::int64_t> sums_;
  std::vector<double> maxima_;
};

using Pass = std::function<vg::VisibilityResult(const vg::VisibilityOptions&)>;

// Every share's result against the one-process result.
void check_shares(const Pass& pass, vg::VisibilityOptions options, int count) {
  const vg::VisibilityResult one = pass(options);
  Exchange exchange(count);
  std::vector<vg::VisibilityResult> shares(static_cast<std::size_t>(count));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
  std::vector<std::thread> threads;
  for (int s = 0; s < count; ++s)
    threads.emplace_back([&, s] {
      vg::VisibilityOptions o = options;
      o.threads = 1;
      o.share.index = s;
      o.share.count = count;
      o.share.combine = [&exchange](std::vector<std::int64_t>& sums, std::vector<double>& maxima) {
        exchange.combine(sums, maxima);
      };
      try {
        shares[static_cast<std::size_t>(s)] = pass(o);
      } catch (...) {
        errors[static_cast<std::size_t>(s)] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  CHECK_FALSE(exchange.mismatch());
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  for (int s = 0; s < count; ++s) {
    INFO("share " << s << " of " << count);
    const vg::VisibilityResult& r = shares[static_cast<std::size_t>(s)];
    CHECK(r.degree == one.degree);
    REQUIRE(r.sum.size() == one.sum.size());
    for (std::size_t k = 0; k < one.sum.size(); ++k) CHECK(same_bits(r.sum[k], one.sum[k]));
    CHECK(same_bits(r.mean_distance, one.mean_distance));
    CHECK(same_bits(r.max_distance, one.max_distance));
    CHECK(r.pruned == one.pruned);
    CHECK(r.pairs_visible == one.pairs_visible);
    CHECK(r.coincident_pairs == one.coincident_pairs);
    CHECK(r.pairs_culled_visible == one.pairs_culled_visible);
    // A packet left to rays is first tried against the occluders that
    // blocked the row's last packets, which depend on the pairs of clusters
    // dealt to the share (packet_culling.hpp): how the undecided pairs split
    // between rays and packet culling may differ, never their sum or a result.
    CHECK(r.pairs_cast + r.pairs_culled_blocked == one.pairs_cast + one.pairs_culled_blocked);
  }
  CHECK(one.pairs_visible > 0);  // the scene has something to share
}

std::vector<Vector3d> layout_nodes(const vg::Scene& scene) {
  vg::NodeGridOptions o;
  o.spacing = 1.0;
  o.walkable = vg::classic_layout_walkable_groups();
  return vg::generate_nodes(scene, o).eyes;
}
}  // namespace

TEST_CASE("pass shares: every path of the pass, identical to one process", "[visgraph][share]") {
  const int layout = GENERATE(0, 1, 2, 3, 4);
  const vg::Scene scene(vg::classic_layout(layout));
  const std::vector<Vector3d> nodes = layout_nodes(scene);
  INFO(vg::classic_layout_name(layout) << ", " << nodes.size() << " nodes");
  const Pass all = [&](const vg::VisibilityOptions& o) { return vg::all_to_all(scene, nodes, o); };
  vg::VisibilityOptions o;
  o.sigmas = {0.0, 1.5e-4, 0.0045, 0.3};
  o.distance_stats = true;
  o.threads = 2;
  const int count = GENERATE(2, 3, 5);
  INFO(count << " shares");
  {
    SECTION("culled") { check_shares(all, o, count); }
    SECTION("every pair cast") {
      o.culling = false;
      check_shares(all, o, count);
    }
    SECTION("pruned") {
      o.sigmas = {4.0};
      o.prune_below = 1e-3;
      check_shares(all, o, count);
    }
    SECTION("distance limit") {
      o.max_distance = 10;
      check_shares(all, o, count);
    }
    SECTION("to targets") {
      const std::vector<Vector3d> targets = {{1, 1, 1.7}, {25, 25, 1.7}, {49, 3, 1.7}};
      check_shares([&](const vg::VisibilityOptions& opt) { return vg::to_targets(scene, nodes, targets, opt); }, o,
                   count);
    }
  }
}

// A share may hand its own lines of sight to an edge sink: the space-syntax
// measures join them across processes (test_space_syntax.cpp checks the
// joined graph against one process's).
TEST_CASE("pass shares: a share that does not exist, or without a combine step, is refused", "[visgraph][share]") {
  const vg::Scene scene(vg::classic_layout(2));
  const std::vector<Vector3d> nodes = {{1, 1, 1.7}, {40, 40, 1.7}};
  vg::VisibilityOptions o;
  o.sigmas = {0.01};
  o.share.count = 2;
  o.share.index = 2;
  o.share.combine = [](std::vector<std::int64_t>&, std::vector<double>&) {};
  CHECK_THROWS_WITH(vg::all_to_all(scene, nodes, o), Catch::Contains("share 2 of 2 does not exist"));
  o.share.index = 1;
  o.share.combine = nullptr;
  CHECK_THROWS_WITH(vg::all_to_all(scene, nodes, o), Catch::Contains("combine"));
}
