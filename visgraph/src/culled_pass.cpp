// The all-to-all pass over leaf clusters (culled_pass.hpp).
#include "culled_pass.hpp"

#include "packet_culling.hpp"
#include "pair_culling.hpp"
#include "progress.hpp"
#include "scene_access.hpp"
#include <attenuvis/visgraph/detail/visible_block.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

namespace attenuvis::visgraph::detail {

namespace {
// The nodes in leaf order: coordinates, x-order row and caller's index of
// each position.
struct LeafLayout {
  Points points;
  std::vector<std::uint32_t> row, caller;
};

LeafLayout leaf_layout(const PairCulling& culling, const Points& rows, const std::uint32_t* caller) {
  LeafLayout layout;
  layout.row = culling.leaf_order();
  const std::size_t N = layout.row.size();
  layout.points.x.resize(N);
  layout.points.y.resize(N);
  layout.points.z.resize(N);
  layout.caller.resize(N);
  for (std::size_t p = 0; p < N; ++p) {
    const std::uint32_t r = layout.row[p];
    layout.points.x[p] = rows.x[r];
    layout.points.y[p] = rows.y[r];
    layout.points.z[p] = rows.z[r];
    layout.caller[p] = caller ? caller[r] : r;
  }
  return layout;
}

// What the leaves' tasks share.
struct LeafPass {
  const Pass& pass;  // rows = positions of `layout`
  const PairCulling& culling;
  const LeafLayout& layout;
  const std::vector<std::uint32_t>& rank_of;  // x-order row of each caller index (edges only)
  Progress& progress;
  const PacketCulling& packets;
};

// The nodes of leaves [begin, end) as a block side (contiguous in leaf order).
BlockSide side_of(const LeafPass& lp, std::size_t begin, std::size_t end) {
  const Points& P = lp.layout.points;
  const std::size_t first = lp.culling.leaf_first(begin);
  return BlockSide{P.x.data(), P.y.data(), P.z.data(), first,
                   static_cast<int>(lp.culling.leaf_end(end - 1) - first)};
}

// Leaf `leaf` against the runs of leaves decided in sight: each pair of
// leaves once (by the one with the smaller index), the later leaves of a
// run as one run of columns.
void score_visible_runs(const LeafPass& lp, std::size_t leaf, ThreadState& ts) {
  const Pass& pass = lp.pass;
  PhaseClock clock(pass.time_phases);
  const BlockSide rows = side_of(lp, leaf, leaf + 1);
  std::uint64_t pairs = 0;
  const auto score = [&](const BlockSide& cols, bool same) {
    const BlockCounts counts =
        score_visible_block(rows, cols, same, pass.neg_sigma.data(), pass.K, pass.max_distance, ts.acc.data(), pass.N,
                            pass.keep_max ? ts.max_distance.data() : nullptr);
    ts.visible += counts.visible;
    ts.coincident += counts.coincident;
    pairs += same ? static_cast<std::uint64_t>(rows.count) * static_cast<std::uint64_t>(rows.count - 1) / 2
                  : static_cast<std::uint64_t>(rows.count) * static_cast<std::uint64_t>(cols.count);
  };
  for (const PairCulling::Run& run : ts.runs) {
    if (run.verdict != Verdict::visible || run.leaf_end <= leaf) continue;
    const bool inside = run.leaf_begin <= leaf;
    if (inside) score(rows, true);
    const std::size_t from = inside ? leaf + 1 : run.leaf_begin;
    if (from < run.leaf_end) score(side_of(lp, from, run.leaf_end), false);
  }
  ts.seconds.score += clock.lap();
  if (pairs) lp.progress.add(pairs);
}

// The leaves whose packets the rows of a leaf run: every leaf of the runs
// cast, and with `dense` false those in sight as well.
void expand_runs(const std::vector<PairCulling::Run>& runs, bool dense, std::vector<PairCulling::Block>& blocks) {
  blocks.clear();
  for (const PairCulling::Run& run : runs) {
    if (dense && run.verdict == Verdict::visible) continue;
    for (std::uint32_t leaf = run.leaf_begin; leaf < run.leaf_end; ++leaf) blocks.push_back({leaf, run.verdict});
  }
}

// After this many packets of one pair of leaves in a row are left to
// rays, the pair's remaining packets are cast without trying (a pair that
// is not blocked near its first rows rarely is further on).
constexpr std::uint8_t kPacketMisses = 3;

// Partners in one chunk of a leaf's blocks (see run_leaf_rows): 96 kB of
// coordinates.  Measured at 2 m on two threads: chunks of 1,024 to 16,384
// partners within 3 %, 4,096 the least.
constexpr std::size_t kChunkPartners = 4096;

// What a row does with one packet of a pair of leaves left to rays
// (packet_culling.hpp): cast it, or skip it, decided blocked.
Verdict decide_packet(const LeafPass& lp, std::size_t i, std::size_t j0, int k, std::size_t b, EyePlane::Fan& fan,
                      ThreadState& ts) {
  if (!lp.packets.active()) return Verdict::cast;
  PhaseClock clock(lp.pass.time_phases);
  const Points& P = lp.layout.points;
  const double point[3] = {P.x[i], P.y[i], P.z[i]};
  const bool occluders = ts.packet_misses[b] < kPacketMisses;
  const Verdict v = lp.packets.decide(point, P.x.data() + j0, P.y.data() + j0, P.z.data() + j0, k, ts.packet_hints[b],
                                      ts.near_hints, fan, i, occluders);
  if (occluders) ts.packet_misses[b] = v == Verdict::cast ? static_cast<std::uint8_t>(ts.packet_misses[b] + 1) : 0;
  if (v == Verdict::blocked) ts.packet_blocked += static_cast<std::uint64_t>(k);
  ts.seconds.classify += clock.lap();
  return v;
}

// Row `row` (at position i) against its partners after it (x order) in
// blocks [b0, b1) of ts.blocks, with its lane totals `row_lanes` and its
// fan; returns the partners.
std::uint64_t row_through_blocks(const LeafPass& lp, std::size_t i, std::uint32_t row, std::size_t b0, std::size_t b1,
                                 std::int64_t* row_lanes, EyePlane::Fan& fan, ThreadState& ts,
                                 std::vector<Edge>* edges) {
  std::uint64_t done = 0;
  for (std::size_t b = b0; b < b1; ++b) {
    const PairCulling::Block& block = ts.blocks[b];
    const std::uint32_t* partners = ts.block_rows[b].rows;
    const std::size_t n = ts.block_rows[b].count;
    if (n == 0 || ts.block_rows[b].last <= row) continue;
    const std::uint32_t* after = partners[0] > row ? partners : std::upper_bound(partners, partners + n, row);
    const std::size_t j0 = ts.block_rows[b].first + static_cast<std::size_t>(after - partners);
    const int k = static_cast<int>(partners + n - after);
    done += static_cast<std::uint64_t>(k);
    const Verdict v = block.verdict == Verdict::cast ? decide_packet(lp, i, j0, k, b, fan, ts) : block.verdict;
    if (v != Verdict::blocked) add_packet(lp.pass, i, nullptr, j0, k, row_lanes, ts, edges, v == Verdict::cast);
  }
  return done;
}

// The rows of leaf `leaf` whose x-order row lies in [row_begin, row_end),
// each against its partners after it (x order) in the leaves of ts.blocks:
// partners culled as visible go through the policy without rays, the rest
// are decided packet by packet or cast.  Edges of a row are put in partner
// order, as in the row-by-row pass.
void run_leaf_rows(const LeafPass& lp, std::size_t leaf, std::size_t row_begin, std::size_t row_end, ThreadState& ts,
                   RowEdges* row_edges) {
  const Pass& pass = lp.pass;
  std::size_t count = 0;
  const std::uint32_t* rows = lp.culling.leaf_rows(leaf, count);
  const std::size_t first = lp.culling.leaf_first(leaf);
  const std::uint32_t* from = std::lower_bound(rows, rows + count, static_cast<std::uint32_t>(row_begin));
  const std::uint32_t* to = std::lower_bound(rows, rows + count, static_cast<std::uint32_t>(row_end));
  ts.packet_hints.assign(ts.blocks.size(), PacketCulling::Hints{});
  ts.packet_misses.assign(ts.blocks.size(), 0);
  ts.near_hints = PacketCulling::Hints{};
  ts.block_rows.resize(ts.blocks.size());
  for (std::size_t b = 0; b < ts.blocks.size(); ++b) {
    ThreadState::BlockRows& br = ts.block_rows[b];
    br.rows = lp.culling.leaf_rows(ts.blocks[b].leaf, br.count);
    br.first = lp.culling.leaf_first(ts.blocks[b].leaf);
    br.last = br.count ? br.rows[br.count - 1] : 0;
  }
  // The rows take the blocks a chunk at a time, every row through one
  // chunk before the next, so that a chunk's partners stay in cache for
  // all the leaf's rows (at 1 m, one row's partners left to rays span more
  // than a core's cache).  Each row keeps its own lane totals and fan.
  // Chunks rather than one partner leaf at a time: the near hints decide
  // more packets when a row's packets follow one another
  // (docs/guide/visgraph-engine.md).
  const std::size_t row_count = static_cast<std::size_t>(to - from);
  const std::size_t lanes = ts.row.size();
  ts.leaf_rows.assign(row_count * lanes, 0);
  const auto lanes_of = [&](std::size_t q) { return ts.leaf_rows.data() + q * lanes; };
  if (ts.fan.size() < row_count) ts.fan.resize(row_count);
  // The q-th row's position, and its edge list (or null).
  const auto position = [&](std::size_t q) { return first + static_cast<std::size_t>(from + q - rows); };
  const auto edges_of = [&](std::size_t q) { return row_edges ? &(*row_edges)[from[q] - row_begin] : nullptr; };
  for (std::size_t q = 0; q < row_count && row_edges; ++q) edges_of(q)->clear();
  std::uint64_t done = 0;
  for (std::size_t chunk = 0; chunk < ts.blocks.size();) {
    std::size_t chunk_end = chunk, partners_in_chunk = 0;
    while (chunk_end < ts.blocks.size() && (chunk_end == chunk || partners_in_chunk < kChunkPartners))
      partners_in_chunk += ts.block_rows[chunk_end++].count;
    for (std::size_t q = 0; q < row_count; ++q)
      done += row_through_blocks(lp, position(q), from[q], chunk, chunk_end, lanes_of(q), ts.fan[q], ts, edges_of(q));
    chunk = chunk_end;
  }
  for (std::size_t q = 0; q < row_count; ++q) {
    const std::size_t i = position(q);
    end_row(pass, i, lanes_of(q), ts);
    std::vector<Edge>* edges = edges_of(q);
    if (edges) {
      const std::uint32_t self = pass.caller[i];
      std::sort(edges->begin(), edges->end(), [&](const Edge& a, const Edge& b) {
        return lp.rank_of[a.i == self ? a.j : a.i] < lp.rank_of[b.i == self ? b.j : b.i];
      });
    }
  }
  if (done) lp.progress.add(done);  // blocked pairs were counted when their clusters were classified
}
}  // namespace

std::vector<std::uint32_t> run_culled_pass(const Scene& scene, const Pass& rows_pass, const VisibilityOptions& options,
                                           tbb::enumerable_thread_specific<ThreadState>& states,
                                           VisibilityResult& result) {
  const std::size_t N = rows_pass.N;
  Progress progress(options.progress, options.on_progress, result.pairs_total, "vg", options.pairs_done,
                    options.cancel);
  tbb::task_arena arena(worker_threads(options));
  std::unique_ptr<PairCulling> culling;
  const Points& sources = *rows_pass.sources;
  arena.execute([&] {
    culling = std::make_unique<PairCulling>(rows_pass.rtc, scene.triangle_count(), sources.x, sources.y, sources.z,
                                            options.culling, &progress, options.share.index, options.share.count);
  });
  result.pairs_culled_visible = culling->pairs_visible();
  result.pairs_culled_blocked = culling->pairs_blocked();
  result.culling_seconds = culling->seconds();
  result.culling_bytes = culling->record_bytes();
  const LeafLayout layout = leaf_layout(*culling, sources, rows_pass.caller);
  Pass pass = rows_pass;
  pass.sources = pass.partners = &layout.points;
  pass.caller = layout.caller.data();
  std::vector<std::uint32_t> rank_of(options.edge_sink ? N : 0);
  for (std::size_t p = 0; p < rank_of.size(); ++p) rank_of[layout.caller[p]] = layout.row[p];
  const std::unique_ptr<EyePlane> plane =
      culling->geometry() && options.eye_plane ? EyePlane::build(*culling->geometry(), layout.points, culling->margin())
                                                   : nullptr;
  const PacketCulling packets(culling->scene(), culling->geometry(), culling->margin(), plane.get());
  const LeafPass lp{pass, *culling, layout, rank_of, progress, packets};
  run_row_blocks(options, N, N, [&](std::size_t block, std::size_t block_end, RowEdges* row_edges) {
    const bool dense = row_edges == nullptr;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, culling->leaf_count(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        ThreadState& ts = states.local();
                        for (std::size_t leaf = range.begin(); leaf != range.end(); ++leaf) {
                          culling->partner_runs(leaf, ts.runs);
                          if (dense) score_visible_runs(lp, leaf, ts);
                          expand_runs(ts.runs, dense, ts.blocks);
                          run_leaf_rows(lp, leaf, block, block_end, ts, row_edges);
                        }
                      });
  });
  progress.finish();
  return layout.caller;
}

}  // namespace attenuvis::visgraph::detail
