// Lines of sight weighted by contrast ratio C = exp(-sigma d).
//
// For every node the library reports, in ONE pass over the rays and for every
// requested extinction coefficient sigma_k (1/m):
//   degree      number of nodes it sees,
//   S_S[k]      = sum over visible partners of exp(-sigma_k d)   (seed paper, "sum score"),
//   S_A[k]      = S_S[k] / degree                                 ("average score"),
//   and optionally the mean and the maximum visible distance.
//
// Line-of-sight policy.  A pair (a, b) of eye points is visible when no
// triangle meets the segment a→b shortened at BOTH ends by
//     gap(d) = 1e-4 m + 1e-6 d,
// the absolute term covering the float rounding of recentred coordinates for
// scenes up to ~1 km from their centre (float spacing 6e-5 m there), the
// relative term the rounding of a direction of length d.  Pairs with d <
// 1e-6 m are coincident: never cast, neither visible nor counted (reported
// as `coincident_pairs`).  all_to_all casts every pair from its end earlier
// in x order (ties by y, z, index), in canonical packets (the row against the
// partners after it in one cluster of <= 16 nearby nodes) whatever outputs
// are asked for and whether or not it culls, so that a segment that just
// touches an edge (Embree's answer then depends on the ray's direction and
// on the packet it travels in) is decided the same way in every run.  Pairs
// with d <= 2 gap(d) but not coincident are visible without a ray (no room
// for geometry between them).
//
// Exact culling (all_to_all without a candidate radius; on by default).
// Clusters of nodes are compared as wholes (src/pair_culling.hpp): a pair of
// clusters whose convex hull, grown by the margin m = 1e-3 m + 1e-5 L (L the
// largest |local coordinate| of a node or vertex), meets no triangle is all
// in sight; one whose sight lines all pass through one planar convex
// occluder, at least m inside it and m from either end, is all blocked.  m
// exceeds the end gap and the float rounding of Embree's rays, so those
// pairs are decided as their rays would be; the rest are cast in the same
// packets as without culling.  Results (degree, S_S bits, distances, edge
// list) are identical with culling on or off.
//
// Determinism.  Contributions are accumulated as 64-bit integers in fixed
// point (C in units of 2^-40, distance in units of 2^-20 m): integer addition
// is associative, so results are bit-identical for any thread count or
// schedule.  The price is rounding each C to 2^-41 (4.5e-13): |S_S error| <=
// partners x 2^-41 in addition to the double evaluation of exp (~2 ulp).
//
// Pruning.  With prune_below = eps in (0, 1) and sigma_min > 0, pairs farther
// than R = pruning_radius(eps, sigmas) = ln(1/eps)/sigma_min are never cast (all-to-all: candidates from the
// slab x_i <= x <= x_i + R of the nodes sorted by x; to_targets: a kd-tree
// radius search).  Each skipped partner would have contributed at most
// exp(-sigma_k R) <= eps to S_S[k], so |S_S error| <= pruned x eps, reported
// per node (`pruned`).  Degree and distance statistics need every pair, so
// they are reported only when no pair within max_distance is pruned.  A
// pruned pass casts every pair within R while the exact pass culls, so
// pruning is applied only when at most 10% of the pairs lie within R along
// x; otherwise the pass runs exact and says so in `pruning_note`, which also
// says what a pruned pass dropped.
#pragma once

#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// One visible pair and its distance.
struct Edge {
  std::uint32_t i, j;  // node indices (targets mode: j indexes the targets)
  double distance;     // m
};

// A pass's progress, once a second from its first second: pairs done
// (cast, or decided without a ray by culling or the line-of-sight policy),
// the rate so far and the time left at that rate (-1: unknown).
struct ProgressReport {
  std::uint64_t pairs_done = 0, pairs_total = 0;
  double seconds = 0, pairs_per_s = 0, seconds_left = -1;
};

// One share of a pass run on several processes (the CLI's MPI layer,
// apps/process_group.hpp).  Every process builds the same cluster tree;
// all-to-all without a radius then expands the top of the dual-tree
// traversal identically everywhere and deals its pairs of clusters to the
// shares by estimated cost (per node pair: cast 4, culled in sight 1, culled
// blocked 0, still undecided 1.5), so that each process classifies and casts
// only its own (src/pair_culling.hpp); every other path deals rows index,
// index + count, ... .  `combine` is then called once, on the calling
// thread, with the share's raw integer accumulators (fixed-point sums,
// counts, counters: an opaque layout of the same length on every share) and
// its per-node maxima; it must replace them in place by the element-wise sum
// and maximum over all shares.  Integer addition is exact and associative
// and every pair is decided and cast exactly as in one process, so the
// result is bit-identical to a one-process pass for any number of shares.
// An edge sink in a shared pass receives the visible pairs this share
// decided: every visible pair reaches exactly one share, and the shares'
// edges together are the one-process edge list (in another order).
struct PassShare {
  int index = 0;  // this process's share, 0 <= index < count
  int count = 1;
  std::function<void(std::vector<std::int64_t>& sums, std::vector<double>& maxima)> combine;
};

// What a visibility pass computes, and how.
struct VisibilityOptions {
  std::vector<double> sigmas;            // extinction coefficients, 1/m, each finite and >= 0
  bool distance_stats = false;           // mean and max visible distance
  // eps (the CLI's --prune-below): partners whose contrast exp(-sigma_min d)
  // is below eps may be skipped; 0 = exact (every pair cast).
  double prune_below = 0;
  double max_distance = std::numeric_limits<double>::infinity();  // farther pairs are not lines of sight
  int threads = 0;                       // 0 = all cores
  // If set, receives the visible edges in blocks (so the edge list is never
  // held whole in memory).  all_to_all: each visible pair once as (i, j),
  // i < j, grouped by the end each pair is cast from, in increasing x of that
  // end (the order the pass visits them); to_targets: (source, target) in
  // source order.  Asking for edges never changes the scores.
  std::function<void(const std::vector<Edge>&)> edge_sink;
  bool progress = false;                 // progress line on stderr, once a second
  // If set, called once a second during the pass (from a watcher thread)
  // with the progress; the Python API and the CLI show it from here.
  std::function<void(const ProgressReport&)> on_progress;
  // Exact culling (all_to_all without pruning or max distance): blocks of
  // pairs decided without rays, results identical to casting every pair.
  // false: every pair cast (the reference the culling is tested against).
  bool culling = true;
  // With culling, where every node stands at one height (flat ground): each
  // row's fan of walls in the eyes' plane decides sight lines before the
  // occluders one by one (src/eye_plane.hpp).  false: without it (tests and
  // benchmarks comparing the two; the results are the same).
  bool eye_plane = true;
  // Prune whenever prune_below > 0 allows it, even where the exact pass would
  // be faster (tests and error studies of the pruning itself).
  bool always_prune = false;
  // For a caller watching the pass from another thread (the Python binding
  // polls for Ctrl-C and reports progress): `pairs_done`, if set, counts the
  // pairs processed so far (of pairs_total); once `cancel` reads true the pass
  // stops after the rows in flight and throws Cancelled.
  std::atomic<std::uint64_t>* pairs_done = nullptr;
  const std::atomic<bool>* cancel = nullptr;
  // Measure where the pass spends its time (VisibilityResult::score_seconds,
  // ray_seconds, packet_culling_seconds): reads the clock around every
  // packet, which costs a few percent; for benchmarks.
  bool phase_times = false;
  // Several processes: this one computes `share` and combines (PassShare).
  // Progress then shows this share's pairs scaled to the whole pass.
  PassShare share;
};

// Thrown by all_to_all and to_targets when VisibilityOptions::cancel was set.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("visibility pass cancelled") {}
};

// The scores of every node for every sigma, and what the pass did.
struct VisibilityResult {
  std::size_t nodes = 0;
  bool degree_exact = true;                 // false: degree/distances withheld (pruning)
  std::vector<std::uint32_t> degree;        // empty unless degree_exact
  std::vector<std::vector<double>> sum;     // sum[k][node] = S_S for sigmas[k]
  std::vector<double> mean_distance;        // empty unless distance_stats && degree_exact; NaN if degree 0
  std::vector<double> max_distance;         // likewise; NaN if degree 0
  std::vector<std::uint32_t> pruned;        // partners not cast per node (pruning), else zeros
  double prune_below = 0;                   // VisibilityOptions::prune_below as applied (0: exact pass run)
  double pruning_radius = std::numeric_limits<double>::infinity();  // m
  std::uint64_t pairs_total = 0;            // pairs considered (unordered, or source x target)
  std::uint64_t pairs_cast = 0;             // pairs given to Embree
  std::uint64_t pairs_visible = 0;
  std::uint64_t coincident_pairs = 0;
  std::uint64_t pairs_culled_visible = 0;   // culling: pairs decided in sight without rays
  std::uint64_t pairs_culled_blocked = 0;   // culling: pairs decided blocked without rays
  double culling_seconds = 0;               // culling: clustering and classification
  std::size_t culling_bytes = 0;            // culling: memory of the cluster pairs' records
  // With VisibilityOptions::phase_times: thread-seconds (steady clock,
  // summed over the pass's threads, this process only) spent deciding
  // packets of cluster pairs left undecided, scoring pairs, and inside
  // Embree.
  double packet_culling_seconds = 0, score_seconds = 0, ray_seconds = 0;
  std::string pruning_note;                 // what pruning dropped and why (empty: not asked)
  double seconds = 0;                       // wall time of the pass

  // S_A for condition k at node i (NaN when degree is 0 or withheld).
  double average(std::size_t k, std::size_t i) const;
  // Certified bound on |S_S error| at node i from pruning.
  double sum_error_bound(std::size_t i) const { return pruned.empty() ? 0.0 : pruned[i] * prune_below; }
};

// The pruning radius R = ln(1/eps)/sigma_min (m): a partner farther than R
// contributes exp(-sigma_k d) < eps to every S_S[k].  Infinite (nothing may
// be pruned) unless 0 < eps < 1 and sigma_min > 0.
double pruning_radius(double prune_below, double sigma_min);
// The same with sigma_min the smallest of `sigmas` (infinite when empty).
double pruning_radius(double prune_below, const std::vector<double>& sigmas);

// Every unordered pair of `eyes` (world frame) once, both ends credited.
VisibilityResult all_to_all(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                            const VisibilityOptions& options);

// Group to group: every source against every target, the source credited
// (the seed's single-point analysis: sources = all nodes, one target).
VisibilityResult to_targets(const Scene& scene, const std::vector<Eigen::Vector3d>& sources,
                            const std::vector<Eigen::Vector3d>& targets, const VisibilityOptions& options);

}  // namespace attenuvis::visgraph
