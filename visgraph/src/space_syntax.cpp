// Space syntax: measure names, the estimate before the pass, and the entry
// points that build the graph (space_syntax.hpp).  The measures themselves
// are in space_syntax_run.cpp and the files it includes.
#include <attenuvis/visgraph/space_syntax.hpp>

#include <attenuvis/io/number_text.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>

#include <tbb/task_arena.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {
const char* const kMeasureNames[kMeasureCount] = {
    "connectivity", "clustering", "clustering-weighted", "control", "controllability", "mean-depth",
    "integration",  "entropy",    "through-vision",      "metric",  "component",       "step-depth"};

std::string known_measures() {
  std::string list;
  for (const char* name : kMeasureNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list + ", or all";
}
}  // namespace

std::string measure_name(Measure m) { return kMeasureNames[static_cast<unsigned>(m)]; }

bool MeasureSet::any_global() const {
  return has(Measure::mean_depth) || has(Measure::integration) || has(Measure::entropy);
}

MeasureSet MeasureSet::all() {
  MeasureSet s;
  for (unsigned m = 0; m < kMeasureCount; ++m)
    if (static_cast<Measure>(m) != Measure::step_depth) s.add(static_cast<Measure>(m));
  return s;
}

MeasureSet parse_measures(const std::string& list) {
  MeasureSet set;
  std::stringstream in(list);
  std::string name;
  bool any = false;
  while (std::getline(in, name, ',')) {
    any = true;
    if (name == "all") {
      const MeasureSet all = MeasureSet::all();
      for (unsigned m = 0; m < kMeasureCount; ++m)
        if (all.has(static_cast<Measure>(m))) set.add(static_cast<Measure>(m));
      continue;
    }
    unsigned m = 0;
    while (m < kMeasureCount && name != kMeasureNames[m]) ++m;
    if (m == kMeasureCount)
      throw std::invalid_argument("--measures: unknown measure '" + name + "' (known: " + known_measures() + ")");
    if (set.has(static_cast<Measure>(m)))
      throw std::invalid_argument("--measures: '" + name + "' given twice");
    set.add(static_cast<Measure>(m));
  }
  if (!any || set.empty()) throw std::invalid_argument("--measures: name at least one measure (" + known_measures() + ")");
  return set;
}

bool parse_graph_storage(const std::string& text, GraphStorage& storage) {
  if (text == "auto") storage = GraphStorage::automatic;
  else if (text == "bit-rows") storage = GraphStorage::bit_rows;
  else if (text == "csr") storage = GraphStorage::csr;
  else return false;
  return true;
}

SpaceSyntaxEstimate estimate_space_syntax(std::size_t nodes, double pairs_bound, const SpaceSyntaxOptions& o) {
  SpaceSyntaxEstimate e;
  const double n = static_cast<double>(nodes);
  const double words = std::ceil(n / 64);
  const double bits = 8 * n * words;
  // CSR: the pairs as they arrive (8 bytes) and the two-way lists (8 bytes).
  const double csr = 16 * pairs_bound + 8 * n;
  e.bit_rows = o.storage == GraphStorage::automatic ? bits <= csr : o.storage == GraphStorage::bit_rows;
  e.graph_bytes = e.bit_rows ? bits : 8 * pairs_bound + 8 * n;
  bool thinned = false;
  for (double s : o.sigmas) thinned = thinned || (s > 0 && o.contrast_threshold > 0);
  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  const double per_thread = 3 * 64 * n + 16 * n * static_cast<double>(o.sigmas.size());  // sweeps, through vision
  const double columns = 8 * n * 24 * static_cast<double>(o.sigmas.size());
  e.peak_bytes = (e.bit_rows ? bits : csr) + (thinned ? e.graph_bytes : 0) + threads * per_thread + columns + 48 * n;
  if (o.measures.has(Measure::clustering_weighted)) {
    e.clustering_weighted_bytes = 8 * n * n;
    e.peak_bytes += e.clustering_weighted_bytes;
  }
  if (o.measures.has(Measure::metric)) e.metric_relaxations = n * 2 * pairs_bound;
  return e;
}

std::string space_syntax_refusal(const SpaceSyntaxEstimate& e, double memory_bytes, std::size_t nodes) {
  if (!(memory_bytes > 0) || e.peak_bytes <= memory_bytes) return "";
  std::string what = "space syntax on " + std::to_string(nodes) + " nodes needs " +
                     io::significant(e.peak_bytes / 1e9, 3) + " GB (the graph as " +
                     (e.bit_rows ? "bit rows" : "CSR lists") + ": " + io::significant(e.graph_bytes / 1e9, 3) + " GB";
  if (e.clustering_weighted_bytes > 0)
    what += "; clustering-weighted's dense contrast rows: " + io::significant(e.clustering_weighted_bytes / 1e9, 3) + " GB";
  return what + "), more than the " + io::significant(memory_bytes / 1e9, 3) +
         " GB allowed: use a coarser --spacing (the graph shrinks as spacing^-4), --max-distance to bound the lines "
         "of sight, or fewer measures (every process of mpirun holds the whole graph, so mpirun shares the time, "
         "not this memory)";
}

const std::vector<double>& SpaceSyntaxResult::values(const std::string& measure, std::size_t k) const {
  for (const SpaceSyntaxColumn& c : columns)
    if (c.measure == measure && c.condition == k) return c.values;
  throw std::out_of_range("space syntax: no column '" + measure + "' for condition " + std::to_string(k));
}

SpaceSyntaxResult space_syntax(const std::vector<Eigen::Vector3d>& eyes, const std::vector<Edge>& edges,
                               const SpaceSyntaxOptions& options) {
  const SpaceSyntaxEstimate e = estimate_space_syntax(eyes.size(), static_cast<double>(edges.size()), options);
  GraphCollector collector(eyes, e.bit_rows);
  collector.add(edges);
  return space_syntax(collector.finish(), options);
}

SpaceSyntaxRun space_syntax(const Scene& scene, const std::vector<Eigen::Vector3d>& eyes,
                            const VisibilityOptions& pass, const SpaceSyntaxOptions& options) {
  const WorkEstimate work = estimate_work(eyes, nullptr, pass);
  const SpaceSyntaxEstimate e = estimate_space_syntax(eyes.size(), work.pairs, options);
  const std::string refusal = space_syntax_refusal(e, physical_memory_bytes(), eyes.size());
  if (!refusal.empty()) throw std::invalid_argument(refusal);
  GraphCollector collector(eyes, e.bit_rows);
  VisibilityOptions with_edges = pass;
  with_edges.edge_sink = collector.sink();
  SpaceSyntaxRun run;
  run.pass = all_to_all(scene, eyes, with_edges);
  run.measures = space_syntax(collector.finish(options.share), options);
  return run;
}

}  // namespace attenuvis::visgraph
