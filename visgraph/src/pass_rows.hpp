// The rows of a visibility pass: per-thread accumulators, one row's packets
// (cast, or scored without rays where culling decided them in sight), and
// the blocks of rows a pass runs in.  Internal to the visgraph library:
// visibility.cpp runs the row-by-row paths with it, culled_pass.cpp the
// all-to-all pass over leaf clusters.
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include "node_points.hpp"
#include "packet_culling.hpp"
#include "pair_culling.hpp"

#include <embree3/rtcore.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace attenuvis::visgraph::detail {

// Seconds spent in each part of a pass, summed over its threads; measured
// only when VisibilityOptions::phase_times asks (reading the clock around
// every packet costs a few percent).
struct PhaseSeconds {
  double classify = 0;  // deciding packets of undecided cluster pairs (PacketCulling)
  double score = 0;     // distances, contrast ratios and fixed-point sums
  double rays = 0;      // inside Embree
};

// A clock that reads the time only when enabled: lap() returns the seconds
// since the previous lap (0 when disabled).  Steady (wall) time: a thread's
// CPU clock is a system call, ~20 times dearer, too dear to read around
// every packet; on a shared machine the phases therefore also count time a
// thread waited for a core, and callers compare their shares.
class PhaseClock {
 public:
  explicit PhaseClock(bool enabled) : enabled_(enabled) {
    if (enabled_) last_ = std::chrono::steady_clock::now();
  }
  double lap() {
    if (!enabled_) return 0;
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point last_;
};

// Per-thread state.  Accumulators are slot-major: acc[s * N + i] with slots
// degree, distance sum, one per sigma, and (slab pruning) partners within
// the radius; i is a row (all-to-all: a node in x order; culled pass: a
// node in leaf order).  Each thread's arrays are separate heap blocks, so
// threads never write to a shared cache line.
struct ThreadState {
  std::vector<std::int64_t> acc;
  std::vector<double> max_distance;
  std::vector<std::uint32_t> candidates, cast_candidates;
  std::vector<PairCulling::Run> runs;
  std::vector<PairCulling::Block> blocks;
  // Per block of the current leaf: its partner leaf's rows, their count,
  // the last of them and the position of the first (looked up once per
  // leaf, not per row).
  struct BlockRows {
    const std::uint32_t* rows;
    std::size_t count, first;
    std::uint32_t last;
  };
  std::vector<BlockRows> block_rows;
  std::vector<PacketCulling::Hints> packet_hints;  // per block: occluders that blocked its last packets
  PacketCulling::Hints near_hints;                  // of the leaf's rows, whatever the block
  std::vector<std::uint8_t> packet_misses;  // per block: packets in a row left undecided
  std::vector<EyePlane::Fan> fan;           // per row of a leaf, once rows need them: their fans in the eyes' plane
  std::vector<std::pair<std::uint32_t, double>> matches;
  std::vector<std::int64_t> c_fixed, row;  // row: per-lane totals of a row (process_row)
  std::vector<std::int64_t> leaf_rows;      // the lane totals of a leaf's rows, row after row
  std::uint64_t cast = 0, visible = 0, coincident = 0;
  // Pairs of cluster pairs left to rays that PacketCulling decided packet
  // by packet without them.
  std::uint64_t packet_blocked = 0;
  PhaseSeconds seconds;
};

struct Pass {
  RTCScene rtc = nullptr;
  const Points* sources = nullptr;
  const Points* partners = nullptr;
  bool symmetric = false;  // all-to-all: credit partners too
  std::size_t N = 0;       // accumulator length (sources)
  int K = 0;
  std::vector<double> neg_sigma;
  double max_distance = 0;
  bool keep_max = false;
  bool time_phases = false;  // fill ThreadState::seconds
  // All-to-all: caller's index of each row, for the edge list.
  const std::uint32_t* caller = nullptr;
  const PassShare* share = nullptr;  // this process's share of the pass
};

// Is row i (any path but the culled one) in this process's share?  Rows are
// dealt round-robin: row costs change slowly with i, so every share gets a
// fair mix.
inline bool row_in_share(const PassShare& share, std::size_t i) {
  return share.count == 1 || i % static_cast<std::size_t>(share.count) == static_cast<std::size_t>(share.index);
}

// An edge in the caller's numbering; all-to-all edges as (smaller, larger).
inline Edge edge(const Pass& pass, std::size_t row, std::uint32_t partner, double distance) {
  if (!pass.caller) return Edge{static_cast<std::uint32_t>(row), partner, distance};
  const std::uint32_t a = pass.caller[row], b = pass.caller[partner];
  return Edge{std::min(a, b), std::max(a, b), distance};
}

// A row is accumulated in lane totals row_lanes[s * 16 + l] (slots s =
// degree, distance, one per sigma; (2 + K) * 16 values, zeroed first): by
// add_packet for each packet of at most 16 partners, then end_row, which
// adds the row's lane totals to its node.  add_packet takes partners
// j0 .. j0 + n - 1 when `cand` is null, else cand[0 .. n).  With cast_rays
// false the partners are known to be in sight (culling): the packet goes
// through the same policy (coincident, close, max distance) without Embree.
void add_packet(const Pass& pass, std::size_t i, const std::uint32_t* cand, std::size_t j0, int n,
                std::int64_t* row_lanes, ThreadState& ts, std::vector<Edge>* edges, bool cast_rays);
void end_row(const Pass& pass, std::size_t i, const std::int64_t* row_lanes, ThreadState& ts);
// Row i against `count` partners in packets of 16 (see add_packet).
void process_row(const Pass& pass, std::size_t i, const std::uint32_t* cand, std::size_t j0, std::size_t count,
                 ThreadState& ts, std::vector<Edge>* edges);

// The pass's worker threads: options.threads, 0 = all cores.
inline int worker_threads(const VisibilityOptions& options) {
  return options.threads > 0 ? options.threads : tbb::task_arena::automatic;
}

// The edges of each row of a block, while the block runs.
using RowEdges = std::vector<std::vector<Edge>>;

// Rows [0, N) in blocks, inside the pass's task arena: `run_block(block,
// block_end, row_edges)` runs the rows of one block; with an edge sink,
// row_edges holds one edge list per row of the block (row r at r - block),
// handed to the sink in row order once the block is done, so that the edge
// list never sits whole in memory (a block is sized to ~4M partner slots).
// Without a sink row_edges is null and the rows form one block.
template <class RunBlock>
void run_row_blocks(const VisibilityOptions& options, std::size_t N, std::size_t partners_per_row,
                    RunBlock&& run_block) {
  const std::size_t block_rows =
      options.edge_sink ? std::max<std::size_t>(1, (std::size_t{1} << 22) / std::max<std::size_t>(partners_per_row, 1))
                        : N;
  RowEdges row_edges(options.edge_sink ? block_rows : 0);
  tbb::task_arena arena(worker_threads(options));
  arena.execute([&] {
    for (std::size_t block = 0; block < N; block += block_rows) {
      const std::size_t block_end = std::min(N, block + block_rows);
      run_block(block, block_end, options.edge_sink ? &row_edges : nullptr);
      if (options.edge_sink) {
        std::vector<Edge> out;
        for (std::size_t i = block; i < block_end; ++i)
          out.insert(out.end(), row_edges[i - block].begin(), row_edges[i - block].end());
        options.edge_sink(out);
      }
    }
  });
}

}  // namespace attenuvis::visgraph::detail
