// Space syntax in weather: the measures of visibility graph analysis (VGA),
// computed exactly on the lines of sight of the visibility pass
// (visibility.hpp), on the graph that a contrast threshold leaves in each
// weather, and weighted by contrast.
//
// References
//   [T01]  A. Turner, M. Doxa, D. O'Sullivan, A. Penn, "From isovists to
//          visibility graphs: a methodology for the analysis of architectural
//          space", Environment and Planning B 28 (2001) 103-121.
//   [HH84] B. Hillier, J. Hanson, The Social Logic of Space, Cambridge
//          University Press (1984), pp. 108-109 (mean depth, relative
//          asymmetry) and the D-value normalisation of integration.
//   [Te93] J. A. F. Teklenburg, H. J. P. Timmermans, A. F. van Wagenberg,
//          "Space syntax: standardised integration measures and some
//          simulations", Environment and Planning B 20 (1993) 347-357.
//   [dmX]  depthmapX (UCL Space Syntax), salalib/vgamodules/vgavisuallocal,
//          vgavisualglobal, vgametric, vgathroughvision and pointdata
//          (sparkPixel2), genlib/pafmath.h: the variants users' numbers come
//          from.  Where depthmapX and the papers differ, the choice is stated.
//   [On05] J.-P. Onnela, J. Saramaki, J. Kertesz, K. Kaski, "Intensity and
//          coherence of motifs in weighted complex networks", Phys. Rev. E 71
//          (2005) 065103 (weighted clustering).
//   [Th14] M. Then et al., "The More the Merrier: Efficient Multi-Source Graph
//          Traversal", PVLDB 8(4) (2014) 449-460 (bit-parallel BFS).
//   [Be12] S. Beamer, K. Asanovic, D. Patterson, "Direction-optimizing
//          breadth-first search", SC'12 (push or pull per level).
//
// The graph.  G: one node per eye point, an edge for every pair the pass
// finds in sight (the pass's line-of-sight policy; no self-loops; a node
// never counts itself as visible, as in depthmapX, whose sparkPixel2 starts
// at depth 1).  d_ij = |x_i - x_j| in metres, evaluated in double from the
// world coordinates as sqrt(dx*dx + dy*dy + dz*dz) without contraction, so
// that an independent program gets the same bits.  For each extinction
// coefficient sigma_k and contrast threshold eps (default 0.02,
// Koschmieder's threshold of detection),
//     C_ij = exp(-sigma_k d_ij),     G_k = { edges of G with C_ij >= eps }
// (eps = 0: G_k = G).  Every measure below is computed on G_k, separately for
// each k, except the weather reach (on G).  N(i) is i's neighbourhood in
// G_k, k_i = |N(i)|.
//
// Local measures [T01; dmX vgavisuallocal, sparkPixel2]
//   connectivity          k_i                                     ("Connectivity")
//   point_first_moment    sum_{j in N(i)} d_ij                    ("Point First Moment")
//   point_second_moment   sum_{j in N(i)} d_ij^2                  ("Point Second Moment")
//   clustering            sum_{j in N(i)} |N(j) & N(i)| / (k_i (k_i - 1))
//                                                                  ("Visual Clustering Coefficient")
//   control               sum_{j in N(i)} 1 / k_j                 ("Visual Control")
//   controllability       k_i / |U(i)|, U(i) = union over j in N(i) of N(j)
//                                                                  ("Visual Controllability")
//   The three visual ones are -1 where k_i <= 1 (depthmapX writes -1 there).
//   U(i) is exactly depthmapX's set: it holds i itself (i sees each of its
//   neighbours), every node two steps away, and a neighbour j of i only when
//   another neighbour of i sees j; so |U(i)| = 1 + #{j in N(i) : |N(j) & N(i)|
//   > 0} + (nodes at step depth 2), which is how it is computed.  depthmapX
//   sums control in float; here in double.  Turner's papers write
//   controllability with the two-step neighbourhood; depthmapX's union is
//   the one users' numbers come from, and the one followed.
//
// Global measures [HH84; Te93; T01; dmX vgavisualglobal, pafmath.h]
//   Breadth-first step depth from each node i over G_k, limited to `radius`
//   steps when radius > 0 (nodes at depth <= radius count; depthmapX's
//   "radius n" is radius = 0 here).  n = nodes reached, i itself included
//   (depthmapX's count, as Hillier & Hanson p. 108), TD = sum of their
//   depths, MD = TD / (n - 1) ("Visual Mean Depth", -1 where n <= 1),
//   n itself is "Visual Node Count".
//     RA  = 2 (MD - 1) / (n - 2)
//     D_n = 2 (n (log2((n + 2) / 3) - 1) + 1) / ((n - 1)(n - 2))   [HH84 via Te93]
//     P_n = 2 (n - log2 n - 1) / ((n - 1)(n - 2))                    [dmX pvalue]
//     integration_hh     = D_n / RA              ("Visual Integration [HH]")
//     integration_pvalue = P_n / RA              ("Visual Integration [P-value]")
//     integration_tekl   = ln((n - 2) / 2) / ln(TD - n + 1)   [Te93] ("[Tekl]")
//   all three -1 unless n > 2 and MD > 1, and [Tekl] also -1 unless
//   TD - n + 1 > 1 (depthmapX's conditions).  With n_d the nodes at depth d >= 1
//   and p_d = n_d / (n - 1):
//     entropy             = -sum_d p_d log2 p_d                     ("Visual Entropy")
//     relativised_entropy =  sum_d p_d log2(p_d / q_d),
//                            q_d = MD^d e^{-MD} / (d + 1)!   ("Visual Relativised Entropy")
//   both -1 where n <= 1.  depthmapX rounds p_d to float in the relativised
//   sum; here it stays double.  step_depth: the depth of each node from the
//   nearest of the chosen origins (depthmapX's "Visual Step Depth" from
//   selected points), -1 where none reaches it.  component_size: the nodes of
//   i's connected component of G_k, i included.
//
// Metric measures [dmX vgametric]
//   l_ij = length of the shortest path from i to j in G_k with edge lengths
//   d (Dijkstra; d_ij itself when i sees j, by the triangle inequality).
//     metric_mean_distance = sum_j l_ij / n   over the n nodes reached, i
//                            included (depthmapX divides by its node count,
//                            which includes i; -1 never occurs: n >= 1).
//   depthmapX relaxes only from nodes next to a blocked cell (a fast
//   approximation of its own); here every edge is relaxed.
//
// Through vision [dmX vgathroughvision]
//   Nodes on a square grid of spacing h (grid_spacing) have cells; for each
//   line of sight (i, j) of G_k the cells its plan projection crosses are
//   walked as depthmapX's quickPixelateLine does (one cell per step along the
//   major axis from cell centre to cell centre; two cells where the line
//   meets a cell boundary exactly), in exact integer arithmetic, the two end
//   cells excluded; every node standing in such a cell counts the line once.
//     through_vision = the number of lines of sight over the node's cell.
//   depthmapX walks each line from both ends, so its "Through vision" is
//   twice this; its walk also skips exact diagonals (|dx| = |dy|, a zero
//   step count), which are walked here.
//
// Weather enters twice: through G_k above, and through contrast weights
// (C_ij of condition k, on G_k):
//   connectivity_weighted  S_S = sum_{j in N(i)} C_ij (the pass's sum score, on G_k)
//   first_moment_weighted  sum_{j in N(i)} C_ij d_ij
//   clustering_weighted    [On05] sum_{j,h in N(i), j != h} (w_ij w_ih w_jh)^{1/3}
//                          / (k_i (k_i - 1)),  w = C / max over G_k's edges of C;
//                          -1 where k_i <= 1 (networkx's clustering with weights)
//   control_weighted       sum_{j in N(i)} C_ij / S_S(j);  -1 where k_i <= 1
//   through_vision_weighted the sum of C_ij over the lines counted above
//   weather_reach          sum_{j != i reached in G} exp(-sigma_k l^G_ij), l^G
//                          the metric shortest path on G itself: defined even
//                          where G_k falls apart.
//
// Exactness.  Counts, depths and sums of depths are integers.  Sums of
// doubles are taken per node in increasing neighbour index; through vision
// accumulates in 64-bit fixed point (C in units of 2^-32, |error| <= lines x
// 2^-33), so that every result is bit-identical for any thread count and
// any number of processes.  Step depths come from a bit-parallel
// multi-source BFS [Th14] (512 origins per sweep, nearby origins together,
// push or pull per level [Be12]): exact, the same depths as one BFS per node.
#pragma once

#include <attenuvis/visgraph/visibility.hpp>

#include <Eigen/Core>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// Koschmieder's threshold of contrast detection, the default eps.
constexpr double kKoschmiederContrast = 0.02;

// What can be asked for, each naming the columns it adds (above).
enum class Measure : unsigned {
  connectivity,         // connectivity, point_first_moment, point_second_moment, connectivity_weighted, first_moment_weighted
  clustering,           // clustering
  clustering_weighted,  // clustering_weighted
  control,              // control, control_weighted
  controllability,      // controllability
  mean_depth,           // mean_depth, node_count
  integration,          // integration_hh, integration_pvalue, integration_tekl
  entropy,              // entropy, relativised_entropy
  through_vision,       // through_vision, through_vision_weighted
  metric,               // metric_mean_distance, weather_reach
  component,            // component_size
  step_depth,           // step_depth (needs origins)
};
constexpr unsigned kMeasureCount = 12;

// A set of measures, one bit each.
class MeasureSet {
 public:
  bool has(Measure m) const { return bits_ >> static_cast<unsigned>(m) & 1u; }
  void add(Measure m) { bits_ |= 1u << static_cast<unsigned>(m); }
  bool empty() const { return bits_ == 0; }
  bool any_global() const;  // a measure that needs step depths
  static MeasureSet all();  // every measure but step_depth (which needs origins)

 private:
  unsigned bits_ = 0;
};

// The command line's spelling: connectivity, clustering, clustering-weighted,
// control, controllability, mean-depth, integration, entropy, through-vision,
// metric, component, step-depth.
std::string measure_name(Measure m);
// "connectivity,integration,..." or "all"; throws std::invalid_argument
// naming an unknown or repeated measure and listing the known ones.
MeasureSet parse_measures(const std::string& list);

// Several processes (the CLI's MPI layer).  Each process collects the
// edges of its share of the pass; `or_words` must replace the vector by the
// bitwise OR over all processes, `gather` by the concatenation in process
// order, `sum` by the element-wise sum (each per-node value is computed by
// one process, the others holding +0.0, so the sum is that value exactly),
// `sum_integers` likewise for integer accumulators.  Origins and nodes are
// dealt in blocks of 512, block b to process b mod count.
struct SpaceSyntaxShare {
  int index = 0;
  int count = 1;
  std::function<void(std::vector<std::uint64_t>&)> or_words, gather;
  std::function<void(std::vector<double>&)> sum;
  std::function<void(std::vector<std::int64_t>&)> sum_integers;
};

// How the lines of sight are held: chosen from the estimate (the smaller of
// N x N bits and 8 bytes per line bound), or forced.  Results are the same.
enum class GraphStorage { automatic, bit_rows, csr };
// "auto", "bit-rows" or "csr"; false (and `storage` unchanged) otherwise.
bool parse_graph_storage(const std::string& text, GraphStorage& storage);

// What space_syntax computes: the conditions' graphs G_k, the measures,
// their radius and how the lines of sight are held.
struct SpaceSyntaxOptions {
  std::vector<double> sigmas;                       // one G_k each (1/m, finite, >= 0)
  GraphStorage storage = GraphStorage::automatic;
  double contrast_threshold = kKoschmiederContrast;  // eps in [0, 1); 0 keeps every line of sight
  int radius = 0;                                   // steps for the global measures; 0 = n (unlimited)
  MeasureSet measures;
  double grid_spacing = 0;                          // h (m) of the node grid: through vision needs it
  std::vector<std::uint32_t> depth_origins;         // step_depth: origin nodes
  int threads = 0;                                  // 0 = all cores
  SpaceSyntaxShare share;
  // Once this reads true the measures stop after the blocks of nodes in
  // flight and space_syntax throws Cancelled (visibility.hpp).
  const std::atomic<bool>* cancel = nullptr;
};

// How the graph is held and what the measures will cost, known before the
// pass: a caller refuses a run that would not fit.
struct SpaceSyntaxEstimate {
  bool bit_rows = true;          // N x N bits (dense); else CSR of uint32 neighbours
  double graph_bytes = 0;        // the graph, and its thinned copy per weather
  double peak_bytes = 0;         // graph, copy, collection and per-thread BFS state
  double metric_relaxations = 0; // upper bound: N x directed edges (metric only)
  double clustering_weighted_bytes = 0;  // dense contrast rows (clustering-weighted only)
};
// `pairs_bound`: an upper bound on the lines of sight (WorkEstimate::pairs).
SpaceSyntaxEstimate estimate_space_syntax(std::size_t nodes, double pairs_bound, const SpaceSyntaxOptions& options);
// "" when the estimate fits in `memory_bytes` (and the metric work under
// its cap), else why not, with the numbers and what to change.
std::string space_syntax_refusal(const SpaceSyntaxEstimate& estimate, double memory_bytes, std::size_t nodes);

// The lines of sight, held for the measures (bit rows or CSR).
class VisibilityGraph {
 public:
  struct Storage;
  VisibilityGraph();
  explicit VisibilityGraph(std::shared_ptr<const Storage> storage);
  std::size_t nodes() const;
  std::uint64_t edges() const;
  bool bit_rows() const;
  double bytes() const;
  const Storage& storage() const { return *storage_; }

 private:
  std::shared_ptr<const Storage> storage_;
};

// Receives a pass's edges (use sink() as VisibilityOptions::edge_sink) and
// builds the graph over `eyes` (the pass's nodes, world frame); with several
// processes finish() joins every share's edges through the share's
// or_words/gather.
class GraphCollector {
 public:
  GraphCollector(const std::vector<Eigen::Vector3d>& eyes, bool bit_rows);
  ~GraphCollector();
  GraphCollector(const GraphCollector&) = delete;
  GraphCollector& operator=(const GraphCollector&) = delete;
  void add(const std::vector<Edge>& block);
  std::function<void(const std::vector<Edge>&)> sink();
  VisibilityGraph finish(const SpaceSyntaxShare& share = {});

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One column: `measure` as listed above (global ones with "_rK" appended
// when radius = K > 0), for condition `condition` (index into sigmas).
struct SpaceSyntaxColumn {
  std::string measure;
  std::size_t condition = 0;
  std::vector<double> values;  // one per node, in the caller's order
};

// The measures as node columns, with each condition's graph in numbers.
struct SpaceSyntaxResult {
  std::vector<SpaceSyntaxColumn> columns;
  std::vector<std::uint64_t> edges;       // per condition: lines of sight in G_k
  std::vector<std::size_t> components;    // per condition: connected components of G_k
  std::vector<int> same_graph_as;         // per condition: an earlier condition with the same G_k, or -1
  bool bit_rows = true;
  double graph_bytes = 0;
  double seconds = 0;                     // the measures (not the pass)

  // The values of `measure` for condition k; throws std::out_of_range.
  const std::vector<double>& values(const std::string& measure, std::size_t k) const;
};

// The measures on a graph built from a pass (or from edges).  Throws
// std::invalid_argument for options out of range, origins out of range,
// through vision without a grid spacing or with nodes off the grid.
SpaceSyntaxResult space_syntax(const VisibilityGraph& graph, const SpaceSyntaxOptions& options);

// The same from an explicit edge list (each pair once, i != j, indices
// < eyes.size(); duplicates are refused).
SpaceSyntaxResult space_syntax(const std::vector<Eigen::Vector3d>& eyes, const std::vector<Edge>& edges,
                               const SpaceSyntaxOptions& options);

// The visibility pass and the measures in one call (one process).
struct SpaceSyntaxRun {
  VisibilityResult pass;
  SpaceSyntaxResult measures;
};
SpaceSyntaxRun space_syntax(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                            const VisibilityOptions& pass, const SpaceSyntaxOptions& options);

}  // namespace attenuvis::visgraph
