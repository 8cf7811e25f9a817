// All-pairs and source-to-target visibility with contrast-ratio scores.
//
// One row per source node: its partners are cast 16 at a time with
// rtcOccluded16, all rays of a packet sharing the row's origin (coherent
// traversal).  Packets are built, scored (vectorised exp across sigmas and
// lanes) and accumulated by branch-free lane loops (pair_packet.cpp,
// contrast_kernel.cpp).  Results go to per-thread integer accumulators in
// fixed point, laid out slot by slot (degree of every node, then distance
// sums, then one array per sigma) so that crediting 16 consecutive partners
// is one vector add per slot; the accumulators are reduced at the end:
// exact, so independent of thread count and schedule.
//
// Partners of a row:
//  - all-to-all without a radius: all j > i (rows = nodes sorted by x: see
//    plan_pass), one packet per leaf cluster of the culling tree, packets of
//    cluster pairs culled as blocked skipped, pairs culled as in sight
//    scored without rays as dense blocks (culled_pass.hpp, pair_culling.hpp);
//    rows are run leaf by leaf, their nodes laid out leaf after leaf;
//  - to_targets without a radius: every target, as contiguous ranges;
//  - all-to-all with a finite radius (pruning or --max-distance): the
//    partners of row r within the radius lie in the slab x_r <= x <= x_r + R
//    after it, filtered by exact distance (no tree search, no per-row sort);
//  - to_targets with a finite radius: a kd-tree radius search (nanoflann),
//    sorted.
#include <attenuvis/visgraph/detail/contrast_kernel.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include "culled_pass.hpp"
#include "node_points.hpp"
#include "pair_packet.hpp"
#include "pass_input.hpp"
#include "pass_rows.hpp"
#include "pass_share.hpp"
#include "progress.hpp"
#include "scene_access.hpp"

#include <embree3/rtcore.h>
#include <nanoflann.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

namespace {
using detail::kCoincident;
using detail::kPruneWorthFraction;
using detail::kContrastScale;
using detail::kDistanceScale;
using detail::check_pass_input;
using detail::kLanes;
using detail::PairPacket;
using detail::Points;
using detail::pairs_within_x;
using detail::sorted_by_x;
using detail::to_local;
using detail::Pass;
using detail::PhaseSeconds;
using detail::RowEdges;
using detail::ThreadState;
using detail::process_row;
using detail::row_in_share;
using detail::run_row_blocks;

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, std::uint32_t>;

// How a pass finds each row's partners (see the file comment).
struct Plan {
  double prune_radius = std::numeric_limits<double>::infinity();  // R = ln(1/eps)/sigma_min
  double radius = 0;         // min(R, max_distance)
  double radius_sq = 0;      // with slack, for candidate searches
  bool pruning = false;      // R < max_distance: partners within max_distance may be skipped
  bool x_order = false;      // rows are the nodes sorted by x
  bool slab = false;         // partners from the x slab (x_order and a finite radius)
  bool use_tree = false;     // partners from a kd-tree radius search
  std::size_t slots = 0;     // accumulator slots per node
  std::size_t within_slot = 0;  // slab only: partners within the radius, per node
};

Plan plan_pass(const VisibilityOptions& options, bool symmetric) {
  Plan plan;
  plan.prune_radius = pruning_radius(options.prune_below, options.sigmas);
  plan.radius = std::min(plan.prune_radius, options.max_distance);
  plan.pruning = plan.prune_radius < options.max_distance;
  // Candidates within a radius are found with a little slack (relative 5e-10
  // plus 1e-6 m) so that no pair within it is missed by rounding;
  // build_packet then applies "d <= max_distance" exactly.
  plan.radius_sq = plan.radius * plan.radius * (1 + 1e-9) + 1e-12;
  // All-to-all works on the nodes sorted by x, whatever the outputs asked
  // for: every pair is then cast from the same end (the earlier in x order) in
  // the same packets of the same rows with or without an edge list, so a
  // grazing sight line cannot be decided one way in one run and the other way
  // in another (Embree's answer for a segment that touches an edge depends on
  // its direction, and on whether its packet is traversed as a packet or ray
  // by ray).  Results are mapped back to the caller's order at the end; edges
  // as they are found.
  plan.x_order = symmetric;
  plan.slab = symmetric && std::isfinite(plan.radius);
  plan.use_tree = !symmetric && std::isfinite(plan.radius);
  plan.within_slot = 2 + options.sigmas.size();
  plan.slots = plan.within_slot + (plan.slab ? 1 : 0);
  return plan;
}

// Partners after row i (x order) within the radius: the slab
// x_i <= x <= x_i + R, filtered by distance.  Counts, for the pruning bound,
// the partners within the radius of both ends.
void slab_candidates(const Points& P, const Plan& plan, std::size_t i, std::size_t N, ThreadState& ts) {
  const double xi = P.x[i], yi = P.y[i], zi = P.z[i];
  const double slab_width = std::sqrt(plan.radius_sq);
  const std::size_t end = static_cast<std::size_t>(
      std::upper_bound(P.x.begin() + static_cast<std::ptrdiff_t>(i + 1), P.x.end(), xi + slab_width) - P.x.begin());
  ts.candidates.clear();
  std::int64_t* within = ts.acc.data() + plan.within_slot * N;
  for (std::size_t j = i + 1; j < end; ++j) {
    const double dx = P.x[j] - xi, dy = P.y[j] - yi, dz = P.z[j] - zi;
    if (dx * dx + dy * dy + dz * dz > plan.radius_sq) continue;
    ts.candidates.push_back(static_cast<std::uint32_t>(j));
    ++within[j];
  }
  within[i] += static_cast<std::int64_t>(ts.candidates.size());
}

// Targets of source i within the radius by kd-tree search, sorted (edges in
// (source, target) order); returns how many lie within the radius.
std::size_t tree_candidates(const KdTree& tree, const Points& S, const Plan& plan, bool symmetric, std::size_t i,
                            ThreadState& ts) {
  const double q[3] = {S.x[i], S.y[i], S.z[i]};
  const std::size_t first = symmetric ? i + 1 : 0;
  ts.matches.clear();
  tree.radiusSearch(q, plan.radius_sq, ts.matches, nanoflann::SearchParams(32, 0, false));
  ts.candidates.clear();
  std::size_t within = 0;
  for (const auto& m : ts.matches) {
    if (symmetric && m.first == i) continue;
    ++within;
    if (m.first >= first) ts.candidates.push_back(m.first);
  }
  std::sort(ts.candidates.begin(), ts.candidates.end());
  return within;
}

// One row: find its partners and cast them.
void run_row(const Pass& pass, const Plan& plan, const KdTree* tree, std::size_t i, ThreadState& ts,
             std::vector<Edge>* edges, std::vector<std::uint32_t>& pruned) {
  const std::size_t N = pass.N;
  const std::size_t M = pass.symmetric ? N : pass.partners->size();
  const std::size_t first = pass.symmetric ? i + 1 : 0;
  if (plan.slab) {
    slab_candidates(*pass.sources, plan, i, N, ts);
    process_row(pass, i, ts.candidates.data(), 0, ts.candidates.size(), ts, edges);
  } else if (tree) {
    const std::size_t within = tree_candidates(*tree, *pass.sources, plan, pass.symmetric, i, ts);
    if (plan.pruning) pruned[i] = static_cast<std::uint32_t>((pass.symmetric ? N - 1 : M) - within);
    process_row(pass, i, ts.candidates.data(), 0, ts.candidates.size(), ts, edges);
  } else {
    process_row(pass, i, nullptr, first, M - first, ts, edges);
  }
}

// Every row, in parallel (run_row_blocks).
void run_rows(const Pass& pass, const Plan& plan, const KdTree* tree, const VisibilityOptions& options,
              tbb::enumerable_thread_specific<ThreadState>& states, std::vector<std::uint32_t>& pruned,
              std::uint64_t pairs_total) {
  const std::size_t N = pass.N;
  const std::size_t M = pass.symmetric ? N : pass.partners->size();
  Progress progress(options.progress, options.on_progress, pairs_total, "vg", options.pairs_done, options.cancel);
  progress.set_scale(options.share.count);
  run_row_blocks(options, N, M, [&](std::size_t block, std::size_t block_end, RowEdges* row_edges) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(block, block_end, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        ThreadState& ts = states.local();
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          if (!row_in_share(options.share, i)) continue;
                          std::vector<Edge>* edges = row_edges ? &(*row_edges)[i - block] : nullptr;
                          if (edges) edges->clear();
                          run_row(pass, plan, tree, i, ts, edges, pruned);
                          progress.add(pass.symmetric ? N - 1 - i : M);
                        }
                      });
  });
  progress.finish();
}

// Exact reduction of the per-thread integer accumulators into `result`, in
// the caller's node order (order[i] = caller index of row i; empty: same).
void collect_results(const tbb::enumerable_thread_specific<ThreadState>& states, const Plan& plan, const Pass& pass,
                     const std::vector<std::uint32_t>& order, std::vector<std::uint32_t> pruned,
                     VisibilityResult& result) {
  const std::size_t N = pass.N;
  const int K = pass.K;
  std::vector<std::int64_t> total(N * plan.slots, 0);
  std::vector<double> max_distance(pass.keep_max ? N : 0, 0.0);
  for (const ThreadState& ts : states) {
    for (std::size_t s = 0; s < total.size(); ++s) total[s] += ts.acc[s];
    for (std::size_t i = 0; i < max_distance.size(); ++i) max_distance[i] = std::max(max_distance[i], ts.max_distance[i]);
    result.pairs_cast += ts.cast;
    result.pairs_visible += ts.visible;
    result.coincident_pairs += ts.coincident;
    result.pairs_culled_blocked += ts.packet_blocked;
    result.packet_culling_seconds += ts.seconds.classify;
    result.score_seconds += ts.seconds.score;
    result.ray_seconds += ts.seconds.rays;
  }
  if (pass.share->count > 1) detail::combine_shares(*pass.share, total, max_distance, pruned, result);
  const auto caller_index = [&](std::size_t i) { return order.empty() ? i : order[i]; };
  if (plan.slab && plan.pruning)
    for (std::size_t i = 0; i < N; ++i)
      pruned[caller_index(i)] =
          static_cast<std::uint32_t>(static_cast<std::int64_t>(N - 1) - total[plan.within_slot * N + i]);
  result.sum.assign(static_cast<std::size_t>(K), std::vector<double>(N));
  for (int k = 0; k < K; ++k) {
    const std::int64_t* t = total.data() + static_cast<std::size_t>(2 + k) * N;
    for (std::size_t i = 0; i < N; ++i)
      result.sum[static_cast<std::size_t>(k)][caller_index(i)] = static_cast<double>(t[i]) / kContrastScale;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A pruned pass that dropped no partner anywhere cast every pair: its
  // degree and distances are exact.
  if (!result.degree_exact && std::all_of(pruned.begin(), pruned.end(), [](std::uint32_t p) { return p == 0; })) {
    result.degree_exact = true;
    result.pruning_note = "nothing pruned: every pair lies within the pruning radius; every column is exact";
  }
  if (result.degree_exact) {
    result.degree.resize(N);
    for (std::size_t i = 0; i < N; ++i) result.degree[caller_index(i)] = static_cast<std::uint32_t>(total[i]);
    if (pass.keep_max) {
      result.mean_distance.resize(N);
      result.max_distance.resize(N);
      for (std::size_t i = 0; i < N; ++i) {
        const std::int64_t deg = total[i];
        result.mean_distance[caller_index(i)] = deg ? static_cast<double>(total[N + i]) / kDistanceScale / deg : nan;
        result.max_distance[caller_index(i)] = deg ? max_distance[i] : nan;
      }
    }
  }
  result.pruned = std::move(pruned);
}

// Pruning pays only when the radius leaves out most pairs (pruning_pays in
// node_points.hpp).  When it does not, the pass runs exact instead
// (options.prune_below set to 0): nothing is pruned and every column is
// exact.  Returns the note that says so, else "".
std::string drop_pruning_unless_worth_it(VisibilityOptions& options, const Points& sources, const Points& partners,
                                         bool symmetric) {
  const Plan asked = plan_pass(options, symmetric);
  if (!asked.pruning || options.always_prune) return "";
  const double total = symmetric ? 0.5 * sources.size() * (sources.size() - 1.0)
                                 : static_cast<double>(sources.size()) * partners.size();
  const double within = pairs_within_x(sources, partners, symmetric, asked.prune_radius);
  if (detail::pruning_pays(within, total)) return "";
  options.prune_below = 0;
  return "nothing pruned: " + std::to_string(static_cast<int>(100 * within / total + 0.5)) +
         "% of the pairs lie within the pruning radius " + std::to_string(asked.prune_radius) + " m, more than the " +
         std::to_string(static_cast<int>(100 * kPruneWorthFraction)) +
         "% for which pruning is faster than the exact pass; every column is exact";
}

// A result before the pass: its size and the pruning as applied.
VisibilityResult new_result(const VisibilityOptions& options, const Plan& plan, std::size_t N, std::size_t M,
                            bool symmetric, const std::string& pruning_note) {
  VisibilityResult result;
  result.nodes = N;
  result.prune_below = options.prune_below;
  result.pruning_radius = plan.prune_radius;
  result.pruning_note = pruning_note;
  result.degree_exact = !plan.pruning;
  result.pairs_total = symmetric ? static_cast<std::uint64_t>(N) * (N - 1) / 2 : static_cast<std::uint64_t>(N) * M;
  return result;
}

// `sources` are the rows (x-sorted for all-to-all, `order` mapping them to
// the caller's indices); all-to-all rows are their own partners.
Pass make_pass(const Scene& scene, const Points& sources, const Points& partners, bool symmetric,
               const VisibilityOptions& options, const std::vector<std::uint32_t>& order) {
  Pass pass;
  pass.rtc = detail::SceneAccess::embree(scene);
  pass.sources = &sources;
  pass.partners = symmetric ? &sources : &partners;
  pass.symmetric = symmetric;
  pass.N = sources.size();
  pass.K = static_cast<int>(options.sigmas.size());
  for (double s : options.sigmas) pass.neg_sigma.push_back(-s);
  pass.max_distance = options.max_distance;
  pass.keep_max = options.distance_stats;
  pass.time_phases = options.phase_times;
  pass.caller = order.empty() ? nullptr : order.data();
  pass.share = &options.share;
  return pass;
}

ThreadState new_thread_state(const Pass& pass, const Plan& plan) {
  ThreadState ts;
  ts.acc.assign(pass.N * plan.slots, 0);
  if (pass.keep_max) ts.max_distance.assign(pass.N, 0.0);
  ts.c_fixed.assign(static_cast<std::size_t>(std::max(pass.K, 1)) * kLanes, 0);
  ts.row.assign((2 + static_cast<std::size_t>(pass.K)) * kLanes, 0);
  return ts;
}

// What a pruned pass dropped, for a result whose degrees it withheld.
std::string pruned_note(const VisibilityResult& result, const Plan& plan, const VisibilityOptions& options) {
  std::uint64_t dropped = 0, nodes_with_drops = 0;
  for (std::uint32_t p : result.pruned) dropped += p, nodes_with_drops += p > 0;
  return "pruned " + std::to_string(dropped) + " partner slots (pairs farther than " +
         std::to_string(plan.prune_radius) + " m, each contributing < " + std::to_string(options.prune_below) +
         " to every S_S) at " + std::to_string(nodes_with_drops) +
         " nodes; degree, averages and distances need every pair and are left out";
}

VisibilityResult run_pass(const Scene& scene, const Points& given_sources, const Points& partners, bool symmetric,
                          const VisibilityOptions& requested) {
  check_pass_input(given_sources, partners, symmetric, requested);
  const auto start_time = std::chrono::steady_clock::now();
  VisibilityOptions options = requested;
  const std::string pruning_note = drop_pruning_unless_worth_it(options, given_sources, partners, symmetric);
  const Plan plan = plan_pass(options, symmetric);
  const std::size_t N = given_sources.size(), M = symmetric ? N : partners.size();
  VisibilityResult result = new_result(options, plan, N, M, symmetric, pruning_note);

  std::vector<std::uint32_t> order;
  Points sorted;
  if (plan.x_order) sorted = sorted_by_x(given_sources, order);
  const Points& sources = plan.x_order ? sorted : given_sources;
  const Pass pass = make_pass(scene, sources, partners, symmetric, options, order);

  std::unique_ptr<KdTree> tree;
  if (plan.use_tree) tree = std::make_unique<KdTree>(3, *pass.partners, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tbb::enumerable_thread_specific<ThreadState> states([&] { return new_thread_state(pass, plan); });
  std::vector<std::uint32_t> pruned(N, 0);
  // The culled pass keeps its nodes in leaf order (culled_pass.hpp): its
  // accumulators map to the caller's nodes through `layout_order`.
  std::vector<std::uint32_t> layout_order;
  if (symmetric && !plan.slab)
    layout_order = detail::run_culled_pass(scene, pass, options, states, result);
  else
    run_rows(pass, plan, tree.get(), options, states, pruned, result.pairs_total);
  collect_results(states, plan, pass, symmetric && !plan.slab ? layout_order : order, std::move(pruned), result);
  if (plan.pruning && result.degree.empty()) result.pruning_note = pruned_note(result, plan, options);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}
}  // namespace

double pruning_radius(double prune_below, double sigma_min) {
  if (!(prune_below > 0 && prune_below < 1 && sigma_min > 0)) return std::numeric_limits<double>::infinity();
  return std::log(1.0 / prune_below) / sigma_min;
}

double pruning_radius(double prune_below, const std::vector<double>& sigmas) {
  if (sigmas.empty()) return std::numeric_limits<double>::infinity();
  return pruning_radius(prune_below, *std::min_element(sigmas.begin(), sigmas.end()));
}

double VisibilityResult::average(std::size_t k, std::size_t i) const {
  if (degree.empty() || degree[i] == 0) return std::numeric_limits<double>::quiet_NaN();
  return sum[k][i] / degree[i];
}

VisibilityResult all_to_all(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                            const VisibilityOptions& options) {
  const Points points = to_local(scene, eyes, "node");
  return run_pass(scene, points, points, true, options);
}

VisibilityResult to_targets(const Scene& scene, const std::vector<Eigen::Vector3d>& sources,
                            const std::vector<Eigen::Vector3d>& targets, const VisibilityOptions& options) {
  const Points s = to_local(scene, sources, "node");
  const Points t = to_local(scene, targets, "target");
  return run_pass(scene, s, t, false, options);
}

}  // namespace attenuvis::visgraph
