// Exact from-region culling for all-to-all visibility: whole blocks of node
// pairs decided without rays.  Internal to the visgraph library.
//
// The nodes are grouped into a binary tree of spatially compact clusters
// (median split on the longest side of each cluster's bounding box, leaves
// of at most kLeafNodes nodes).  A dual-tree traversal (as in Barnes–Hut, or
// the shaft culling of Haines & Wallace 1994) classifies pairs of clusters
// A, B; every segment between a node of A and a node of B lies in the convex
// hull H of the two bounding boxes, so
//   - visible: no triangle meets H grown by the margin m (separating-axis
//     test, conservative: an axis that separates proves it, the axes tried
//     are the box axes, the triangle normal and cross products of triangle
//     edges with the box axes and with the centre-to-centre direction);
//     then every pair is a line of sight;
//   - blocked: one planar convex occluder (a triangle, or two coplanar
//     triangles sharing an edge that form a convex quad) has every corner of
//     A at distance >= m on one side of its plane and every corner of B at
//     distance >= m on the other, and the crossings of the 64 corner-to-corner
//     segments with the plane lie inside the polygon by at least m.  The
//     crossing of any segment between the boxes is a convex combination of
//     those crossings (the cross-section of H with the plane is their convex
//     hull), so every sight line passes through the polygon's interior, at
//     least m from both ends.  The occluders tried are the surfaces hit by
//     the ray between the two boxes' centres: the first, then further ones
//     while the surfaces met belong to solids (up to kOccluderTries of them).
// Otherwise the larger cluster is split; a pair of leaves still undecided is
// cast.
//
// Packets.  Embree's answer for a segment that grazes an edge may depend on
// the other rays of its packet (its packet and single-ray traversals round
// differently, and it switches between them by the number of active lanes).
// So the packets are canonical: row i against the partners after it (x
// order) in one leaf cluster, <= 16 of them, is one packet, whether the pass
// culls or not (the pass without culling is this class with `classify`
// false: every leaf pair cast).  A culled pass casts exactly the packets the
// full pass casts for the leaf pairs it leaves undecided, so every pair gets
// the same answer.
//
// Shares.  A pass run on several processes (PassShare) expands the top of
// the traversal identically on every process and deals the pairs of
// clusters to them by estimated cost (traverse_share); each process then
// classifies and records only its own, so its rows credit only its own
// blocks, every verdict is the one-process one, and no process repeats the
// others' classification.
//
// Margin.  m = 1e-3 m + 1e-5 L, L the largest |coordinate| (local frame) of
// any node or vertex.  It covers: the end gap of the line-of-sight policy
// (1e-4 m + 1e-6 d, d <= 2 sqrt(3) L), the rounding of a node to a float ray
// origin (<= 6e-8 L), of its direction (<= 6e-8 d), and Embree's own
// rounding inside its watertight triangle test (a few float ulps of the
// coordinates, ~1e-7 L).  So a block decided here is decided the same way as
// Embree decides each of its rays, and the results are identical to casting
// every pair (tests compare them bit for bit).  Decisions nearer a boundary
// than m are left to rays.
#pragma once

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace attenuvis::visgraph {
class Progress;
}

namespace attenuvis::visgraph::detail {

struct Box3;
class CullGeometry;

enum class Verdict : std::uint8_t { visible, blocked, cast };

class PairCulling {
 public:
  static constexpr std::uint32_t kLeafNodes = 16;  // = the packet width: one packet per row and leaf
  static constexpr int kOccluderTries = 4;
  static constexpr std::size_t kItemsPerShare = 32;  // pairs of clusters dealt to each share

  // x, y, z: the nodes (local frame), indexed by row.  Builds the cluster
  // tree and, with `classify`, classifies every pair of clusters (in
  // parallel in the current TBB arena); without, every pair is left to rays.
  // Pairs decided blocked are added to `progress` (if any) as they are found.
  // With share_count > 1, only this share's pairs of clusters are
  // classified and recorded (traverse_share): its rows credit only them.
  PairCulling(RTCScene scene, std::size_t triangle_count, const std::vector<double>& x,
              const std::vector<double>& y, const std::vector<double>& z, bool classify, Progress* progress,
              int share_index = 0, int share_count = 1);

  struct Block {
    std::uint32_t leaf;  // partner leaf
    Verdict verdict;     // visible or cast (blocked blocks are never listed)
  };
  std::size_t leaf_count() const { return leaf_nodes_.size(); }
  // Rows of leaf l, increasing.
  const std::uint32_t* leaf_rows(std::size_t l, std::size_t& count) const;
  // Every row once, leaf after leaf (leaf_rows(l) starts at leaf_first(l)):
  // the order in which the pass lays out its nodes, so that a leaf's nodes
  // are contiguous.
  const std::vector<std::uint32_t>& leaf_order() const { return rows_; }
  std::size_t leaf_first(std::size_t l) const { return nodes_[leaf_nodes_[l]].begin; }
  // Every leaf some of whose pairs with leaf l are not blocked (l itself
  // included when it is), with the verdict.
  void partner_blocks(std::size_t l, std::vector<Block>& out) const;
  // The same as runs of consecutive leaves (one per record; their nodes are
  // contiguous in leaf order): leaves [leaf_begin, leaf_end).
  struct Run {
    std::uint32_t leaf_begin, leaf_end;
    Verdict verdict;
  };
  void partner_runs(std::size_t l, std::vector<Run>& out) const;
  // One past the last position of leaf l's nodes in leaf_order().
  std::size_t leaf_end(std::size_t l) const { return nodes_[leaf_nodes_[l]].end; }

  // The tests a pass uses to decide packets one by one (packet_culling.hpp);
  // null without classification.
  const CullGeometry* geometry() const { return geometry_.get(); }
  RTCScene scene() const { return scene_; }

  std::uint64_t pairs_blocked() const { return pairs_blocked_; }  // unordered pairs decided blocked
  std::uint64_t pairs_visible() const { return pairs_visible_; }  // unordered pairs decided visible
  std::uint64_t cluster_tests() const { return tests_; }
  double margin() const { return margin_; }
  double seconds() const { return seconds_; }

  struct Node {
    double lo[3], hi[3];
    std::uint32_t begin = 0, end = 0;            // rows_[begin, end)
    std::uint32_t leaf_begin = 0, leaf_end = 0;  // leaves under this node
    std::int32_t left = -1, right = -1, parent = -1;
    std::uint32_t size() const { return end - begin; }
    bool is_leaf() const { return left < 0; }
  };
  // A visible or cast record of a node: the other node of the pair of
  // clusters and the verdict, in four bytes (the top bit: cast), half of
  // what the padded pair of an id and a verdict took: a fine grid has
  // hundreds of millions of them.
  struct Record {
    std::uint32_t bits;
    std::uint32_t other() const { return bits & ~kCastBit; }
    Verdict verdict() const { return bits & kCastBit ? Verdict::cast : Verdict::visible; }
    static constexpr std::uint32_t kCastBit = 1u << 31;
  };
  // Bytes the records hold (reported with the pass's statistics).
  std::size_t record_bytes() const { return records_.size() * sizeof(Record); }

 private:
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::int32_t parent);
  void decide(std::size_t triangle_count, bool classify, int share_index, int share_count);
  struct Local;
  enum class Step { empty, visible, blocked, cast, split };
  double pairs_of(std::uint32_t a, std::uint32_t b) const;
  Step visit(std::uint32_t a, std::uint32_t b, bool classify_pairs, Local& local,
             std::vector<std::pair<std::uint32_t, std::uint32_t>>& children) const;
  Step traverse(std::uint32_t a, std::uint32_t b, tbb::enumerable_thread_specific<Local>& locals);
  void traverse_share(bool classify_pairs, int index, int count, tbb::enumerable_thread_specific<Local>& locals);
  void collect(tbb::enumerable_thread_specific<Local>& locals);
  template <class F>
  void for_each_record(std::size_t l, F f) const;
  static double margin_for(const CullGeometry& geometry, const std::vector<double>& x, const std::vector<double>& y,
                           const std::vector<double>& z);
  Verdict classify(std::uint32_t a, std::uint32_t b) const;
  Verdict classify_boxes(const Box3& a, const Box3& b) const;

  RTCScene scene_;
  Progress* progress_ = nullptr;
  const std::vector<double>&x_, &y_, &z_;
  double margin_ = 0;
  std::vector<std::uint32_t> rows_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> leaf_nodes_;
  // Per node x, records_[first_record_[x], first_record_[x + 1]): its
  // visible and cast records (each pair of clusters under both of its
  // nodes), by the other node.
  std::vector<std::uint64_t> first_record_;
  std::vector<Record> records_;
  std::uint64_t pairs_blocked_ = 0, pairs_visible_ = 0, tests_ = 0;
  double seconds_ = 0;
  std::unique_ptr<CullGeometry> geometry_;  // null when not classifying

 public:
  ~PairCulling();
  PairCulling(const PairCulling&) = delete;
  PairCulling& operator=(const PairCulling&) = delete;
};

}  // namespace attenuvis::visgraph::detail
