// space_syntax(graph, options): the weathers' graphs G_k, each measure on
// each, the shares of several processes joined, the columns in the caller's
// node order.
#include "space_syntax_global.hpp"
#include "space_syntax_depth.hpp"

#include <attenuvis/io/check.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

namespace {
using namespace space_syntax_detail;

// Metric shortest paths relax at most N x (directed edges) times; above
// this a run would take hours (about 1e8 relaxations a second per core).
constexpr double kMaxMetricRelaxations = 1e11;

// Columns in internal node order, by measure then condition, in the order
// they were first asked for.
class Columns {
 public:
  Columns(std::size_t conditions, std::size_t nodes) : conditions_(conditions), nodes_(nodes) {}
  std::vector<double>& at(const std::string& measure, std::size_t k) {
    auto it = values_.find(measure);
    if (it == values_.end()) {
      order_.push_back(measure);
      it = values_.emplace(measure, std::vector<std::vector<double>>(conditions_, std::vector<double>(nodes_, 0.0))).first;
    }
    return it->second[k];
  }
  const std::vector<std::string>& order() const { return order_; }
  std::vector<std::vector<double>>& all(const std::string& measure) { return values_.at(measure); }

 private:
  std::size_t conditions_, nodes_;
  std::vector<std::string> order_;
  std::map<std::string, std::vector<std::vector<double>>> values_;
};

void validate(const SpaceSyntaxOptions& o, const Storage& g) {
  for (double s : o.sigmas)
    if (!std::isfinite(s) || s < 0) throw std::invalid_argument("space syntax: sigma must be finite and >= 0 (1/m)");
  if (o.sigmas.empty()) throw std::invalid_argument("space syntax: give at least one sigma (one graph per weather)");
  if (!(o.contrast_threshold >= 0 && o.contrast_threshold < 1))
    throw std::invalid_argument("space syntax: the contrast threshold must lie in [0, 1)");
  if (o.radius < 0) throw std::invalid_argument("space syntax: the radius must be n (0) or a positive number of steps");
  if (o.threads < 0) throw std::invalid_argument("space syntax: thread count must be >= 0");
  if (o.share.count < 1 || o.share.index < 0 || o.share.index >= o.share.count)
    throw std::invalid_argument("space syntax: share " + std::to_string(o.share.index) + " of " +
                                std::to_string(o.share.count) + " does not exist");
  if (o.share.count > 1 && (!o.share.sum || !o.share.sum_integers))
    throw std::invalid_argument("space syntax: several shares need sum steps");
  if (o.measures.has(Measure::step_depth) && o.depth_origins.empty())
    throw std::invalid_argument("space syntax: step depth needs at least one origin");
  for (std::uint32_t origin : o.depth_origins)
    if (origin >= g.n)
      throw std::invalid_argument("space syntax: origin " + std::to_string(origin) + " is not one of the " +
                                  std::to_string(g.n) + " nodes");
}

std::string radius_suffix(int radius) { return radius > 0 ? "_r" + std::to_string(radius) : ""; }

// Which conditions share a graph: same[k] = the first earlier condition
// whose threshold keeps exactly the same lines, else -1; kept[k] = lines
// kept (kept[k] = m: G_k is G itself).
void plan_graphs(const Storage& g, const SpaceSyntaxOptions& o, std::vector<std::uint64_t>& kept,
                 std::vector<int>& same) {
  const std::size_t K = o.sigmas.size();
  const double eps = o.contrast_threshold;
  kept.assign(K, 0);
  same.assign(K, -1);
  std::vector<std::uint8_t> differs(K * K, 0), in(K, 0);
  std::vector<Threshold> threshold;
  for (double sigma : o.sigmas) threshold.emplace_back(sigma, eps);
  for (std::size_t i = 0; i < g.n; ++i)
    for_each_neighbour(g, i, [&](std::uint32_t j) {
      if (j < i) return;
      const double d = g.distance(i, j);
      for (std::size_t k = 0; k < K; ++k) {
        in[k] = threshold[k].keeps(d);
        kept[k] += in[k];
        for (std::size_t m = 0; m < k; ++m) differs[k * K + m] |= in[k] != in[m];
      }
    });
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t m = 0; m < k && same[k] < 0; ++m)
      if (same[m] < 0 && !differs[k * K + m]) same[k] = static_cast<int>(m);
}

// The measures that depend only on G_k, for condition k.
void unweighted_measures(const Storage& gk, const SpaceSyntaxOptions& o, const Owned& owned, std::size_t k,
                         Columns& cols, std::size_t& components) {
  const MeasureSet& m = o.measures;
  const std::string r = radius_suffix(o.radius);
  const bool local = m.has(Measure::connectivity) || m.has(Measure::clustering) || m.has(Measure::control) ||
                     m.has(Measure::controllability);
  // One set of sweeps serves the global measures and controllability's
  // nodes at depth 2 (a radius of 1 stops the sweeps too early for them).
  GlobalColumns gl;
  const bool controllability = m.has(Measure::controllability);
  if (m.any_global()) gl = global_measures(gk, o.radius, controllability, owned, o.threads);
  else if (controllability) gl = global_measures(gk, 2, true, owned, o.threads);
  if (local) {
    const LocalColumns l = local_measures(gk, owned, m.has(Measure::clustering) || controllability, o.threads);
    if (m.has(Measure::connectivity)) {
      cols.at("connectivity", k) = l.connectivity;
      cols.at("point_first_moment", k) = l.first_moment;
      cols.at("point_second_moment", k) = l.second_moment;
    }
    if (m.has(Measure::clustering)) cols.at("clustering", k) = l.clustering;
    if (m.has(Measure::control)) cols.at("control", k) = l.control;
    if (controllability) {
      std::vector<double>& c = cols.at("controllability", k);
      for (std::size_t i = 0; i < gk.n; ++i) {
        const double degree = l.connectivity[i];
        c[i] = degree > 1 ? degree / (1.0 + l.linked_neighbours[i] + gl.at_depth_two[i]) : -1.0;
      }
    }
  }
  if (m.any_global()) {
    if (m.has(Measure::mean_depth)) {
      cols.at("mean_depth" + r, k) = gl.mean_depth;
      cols.at("node_count" + r, k) = gl.node_count;
    }
    if (m.has(Measure::integration)) {
      cols.at("integration_hh" + r, k) = gl.integration_hh;
      cols.at("integration_pvalue" + r, k) = gl.integration_pvalue;
      cols.at("integration_tekl" + r, k) = gl.integration_tekl;
    }
    if (m.has(Measure::entropy)) {
      cols.at("entropy" + r, k) = gl.entropy;
      cols.at("relativised_entropy" + r, k) = gl.relativised_entropy;
    }
  }
  const std::vector<std::uint32_t> sizes = component_sizes(gk, &components);
  if (m.has(Measure::component)) {
    std::vector<double>& c = cols.at("component_size", k);
    for (std::size_t i = 0; i < gk.n; ++i) c[i] = sizes[i];
  }
  if (m.has(Measure::step_depth)) {
    std::vector<std::uint32_t> origins;
    for (std::uint32_t o_caller : o.depth_origins) origins.push_back(gk.internal[o_caller]);
    const std::vector<int> depth = step_depths(gk, origins);
    std::vector<double>& c = cols.at("step_depth", k);
    for (std::size_t i = 0; i < gk.n; ++i) c[i] = depth[i];
  }
}

// The contrast-weighted measures of the conditions in `group`, which share G_k.
void weighted(const Storage& gk, const SpaceSyntaxOptions& o, const Owned& owned, const std::vector<std::size_t>& group,
              Columns& cols) {
  const MeasureSet& m = o.measures;
  if (!m.has(Measure::connectivity) && !m.has(Measure::control) && !m.has(Measure::clustering_weighted)) return;
  std::vector<double> sigmas;
  for (std::size_t k : group) sigmas.push_back(o.sigmas[k]);
  std::vector<WeightedColumns> w = weighted_measures(gk, sigmas, owned, m.has(Measure::control),
                                                     m.has(Measure::clustering_weighted), o.threads);
  for (std::size_t t = 0; t < group.size(); ++t) {
    const std::size_t k = group[t];
    if (m.has(Measure::connectivity)) {
      cols.at("connectivity_weighted", k) = std::move(w[t].sum);
      cols.at("first_moment_weighted", k) = std::move(w[t].first_moment);
    }
    if (m.has(Measure::control)) cols.at("control_weighted", k) = std::move(w[t].control);
    if (m.has(Measure::clustering_weighted)) cols.at("clustering_weighted", k) = std::move(w[t].clustering);
  }
}

void refuse_metric_beyond_cap(const Storage& g, const Owned& owned) {
  const double relaxations = static_cast<double>(g.n) / owned.count * 2.0 * static_cast<double>(g.m);
  if (relaxations > kMaxMetricRelaxations)
    throw std::invalid_argument(
        "metric: shortest paths from " + std::to_string(g.n) + " nodes over " + std::to_string(g.m) +
        " lines of sight relax up to " + std::to_string(relaxations) + " edges per process, above the 1e11 (hours) "
        "this program accepts: leave metric out, use a coarser spacing (the work falls as spacing^-6), fewer nodes, "
        "or more processes (mpirun)");
}

// metric_mean_distance over G_k for each condition in `conditions`, and
// (with reach) weather_reach of every condition over this graph, G.
void metric_measures(const Storage& g, const SpaceSyntaxOptions& o, const Owned& owned,
                     const std::vector<std::size_t>& conditions, bool reach, Columns& cols) {
  refuse_metric_beyond_cap(g, owned);
  const std::size_t K = o.sigmas.size();
  std::vector<std::vector<double>*> mean, weather;
  for (std::size_t k : conditions) mean.push_back(&cols.at("metric_mean_distance", k));
  if (reach)
    for (std::size_t k = 0; k < K; ++k) weather.push_back(&cols.at("weather_reach", k));
  shortest_paths(g, owned, o.threads, [&](std::size_t s, const std::vector<double>& length) {
    double total = 0;
    std::uint64_t reached = 0;
    for (std::size_t j = 0; j < g.n; ++j)
      if (std::isfinite(length[j])) total += length[j], ++reached;
    for (auto* c : mean) (*c)[s] = total / static_cast<double>(reached);
    for (std::size_t k = 0; k < weather.size(); ++k) {
      double sum = 0;
      for (std::size_t j = 0; j < g.n; ++j)
        if (j != s && std::isfinite(length[j])) sum += std::exp(-o.sigmas[k] * length[j]);
      (*weather[k])[s] = sum;
    }
  });
}

void through_vision_measures(const Storage& g, const SpaceSyntaxOptions& o, const Owned& owned, Columns& cols) {
  ThroughVision tv = through_vision(g, o.grid_spacing, o.sigmas, o.contrast_threshold, owned, o.threads);
  const std::size_t K = o.sigmas.size();
  if (o.share.count > 1) {
    std::vector<std::int64_t> flat;
    for (std::size_t k = 0; k < K; ++k) {
      flat.insert(flat.end(), tv.counts[k].begin(), tv.counts[k].end());
      flat.insert(flat.end(), tv.weighted[k].begin(), tv.weighted[k].end());
    }
    o.share.sum_integers(flat);
    for (std::size_t k = 0, at = 0; k < K; ++k) {
      std::copy(flat.begin() + at, flat.begin() + at + g.n, tv.counts[k].begin());
      std::copy(flat.begin() + at + g.n, flat.begin() + at + 2 * g.n, tv.weighted[k].begin());
      at += 2 * g.n;
    }
  }
  for (std::size_t k = 0; k < K; ++k) {
    std::vector<double>& c = cols.at("through_vision", k);
    std::vector<double>& w = cols.at("through_vision_weighted", k);
    for (std::size_t i = 0; i < g.n; ++i) {
      c[i] = static_cast<double>(tv.counts[k][i]);
      w[i] = static_cast<double>(tv.weighted[k][i]) / kThroughVisionScale;
    }
  }
}
}  // namespace

namespace {
// Each column holds the owned nodes' values and +0.0 elsewhere; the sum over
// the processes is then every node's value exactly.  -0.0 becomes +0.0
// (x + 0.0) in every run, so that one process writes what several do.
void join_shares(const SpaceSyntaxOptions& o, const Owned& owned, Columns& cols, std::size_t n) {
  std::vector<double> flat;
  for (const std::string& name : cols.order())
    for (std::vector<double>& c : cols.all(name))
      for (std::size_t i = 0; i < n; ++i) {
        c[i] = owned(i) ? c[i] + 0.0 : 0.0;
        if (o.share.count > 1) flat.push_back(c[i]);
      }
  if (o.share.count <= 1) return;
  o.share.sum(flat);
  std::size_t at = 0;
  for (const std::string& name : cols.order())
    for (std::vector<double>& c : cols.all(name))
      for (std::size_t i = 0; i < n; ++i) c[i] = flat[at++];
}

SpaceSyntaxResult caller_order(const Storage& g, const SpaceSyntaxOptions& o, Columns& cols) {
  SpaceSyntaxResult result;
  for (const std::string& name : cols.order()) {
    std::vector<std::vector<double>>& per_condition = cols.all(name);
    for (std::size_t k = 0; k < o.sigmas.size(); ++k) {
      SpaceSyntaxColumn c;
      c.measure = name;
      c.condition = k;
      c.values.resize(g.n);
      for (std::size_t i = 0; i < g.n; ++i) c.values[g.caller[i]] = per_condition[k][i];
      std::vector<double>().swap(per_condition[k]);
      result.columns.push_back(std::move(c));
    }
  }
  return result;
}
}  // namespace

SpaceSyntaxResult space_syntax(const VisibilityGraph& graph, const SpaceSyntaxOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const Storage& g = graph.storage();
  validate(o, g);
  const std::size_t K = o.sigmas.size();
  const Owned owned{o.share.index, o.share.count, o.cancel};
  Columns cols(K, g.n);
  std::vector<std::uint64_t> kept;
  std::vector<int> same;
  plan_graphs(g, o, kept, same);
  std::vector<std::size_t> components(K, 0);
  std::vector<std::size_t> metric_on_g;  // conditions whose G_k is G
  for (std::size_t k = 0; k < K; ++k) {
    if (same[k] >= 0) continue;
    std::unique_ptr<Storage> own;
    const Threshold threshold(o.sigmas[k], o.contrast_threshold);
    if (kept[k] < g.m)
      own = std::make_unique<Storage>(
          thinned(g, [&](std::size_t i, std::size_t j) { return threshold.keeps(g.distance(i, j)); }));
    const Storage& gk = own ? *own : g;
    std::vector<std::size_t> group = {k};
    for (std::size_t m = k + 1; m < K; ++m)
      if (same[m] == static_cast<int>(k)) group.push_back(m);
    unweighted_measures(gk, o, owned, k, cols, components[k]);
    for (std::size_t m : group)
      if (m != k) {
        for (const std::string& name : cols.order()) cols.at(name, m) = cols.at(name, k);
        components[m] = components[k];
      }
    weighted(gk, o, owned, group, cols);
    if (o.measures.has(Measure::metric)) {
      if (own) metric_measures(gk, o, owned, group, false, cols);
      else metric_on_g.insert(metric_on_g.end(), group.begin(), group.end());
    }
  }
  if (o.measures.has(Measure::metric)) metric_measures(g, o, owned, metric_on_g, true, cols);
  if (o.measures.has(Measure::through_vision)) through_vision_measures(g, o, owned, cols);
  if (owned.cancelled()) throw Cancelled();
  join_shares(o, owned, cols, g.n);
  SpaceSyntaxResult result = caller_order(g, o, cols);
  result.edges = kept;
  result.components = components;
  result.same_graph_as = same;
  result.bit_rows = g.dense;
  result.graph_bytes = g.bytes();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace attenuvis::visgraph
