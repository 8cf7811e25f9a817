// Section 3: the seed's five classic 50x50 m layouts at 1 m spacing, eye
// height 1.7 m (seed paper, Sec. Results / Visibility Graph Case, Figs.
// count, vg_clear, vg_weather, vg_ab).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "attenuvis/visgraph/visibility.hpp"
#include "sections.hpp"

namespace attenuvis::validation::detail {

namespace {

namespace vg = attenuvis::visgraph;

struct Range {
  double min = 0, max = 0, mean = 0;
};
Range range_of(const std::vector<double>& v) {
  Range r;
  if (v.empty()) return r;
  r.min = *std::min_element(v.begin(), v.end());
  r.max = *std::max_element(v.begin(), v.end());
  r.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  return r;
}

struct LayoutRun {
  int index = 0;
  std::string name;
  std::vector<Eigen::Vector3d> eyes;
  std::vector<double> x, y, z, degree;
  std::vector<std::vector<double>> ss;        // per all-to-all condition
  std::size_t corner = 0;                      // bottom-left node
  std::vector<std::vector<double>> corner_c;   // per single-point condition: C of each node to the corner
  double obstacle_area = 0;
  std::size_t ss_above_degree = 0;
  double seconds = 0;
  std::uint64_t pairs = 0;
};


// The conditions of the seed's Figs. vg_clear and vg_weather (all pairs) and
// of Fig. vg_ab (to one point), with their sigma.
struct LayoutConditions {
  std::vector<VgCondition> all, point;
  std::vector<double> all_sigmas, point_sigmas;
};
LayoutConditions layout_conditions(const SeedConditions& seed) {
  LayoutConditions c;
  for (const char* name : {"clear", "rain:8", "fog:advection", "snow:dry:4"})
    for (auto& v : vg_conditions(seed, name)) c.all.push_back(v);
  for (const char* name : {"clear", "rain:8", "snow:dry:4"})
    for (auto& v : vg_conditions(seed, name)) c.point.push_back(v);
  for (auto& v : c.all) c.all_sigmas.push_back(v.sigma);
  for (auto& v : c.point) c.point_sigmas.push_back(v.sigma);
  return c;
}

// Layout k at 1 m spacing, eyes 1.7 m: all pairs, then every node to the
// bottom-left corner node.
LayoutRun run_layout(Context& ctx, int k, const LayoutConditions& conds) {
  const double spacing = 1.0, eye = 1.7;
  ctx.step("layouts", std::string("layout ") + std::to_string(k) + " (" + vg::classic_layout_name(k) + ")");
  const auto t0 = std::chrono::steady_clock::now();
  LayoutRun r;
  r.index = k;
  r.name = vg::classic_layout_name(k);
  for (const auto& f : vg::classic_layout_obstacles(k)) r.obstacle_area += (f.x1 - f.x0) * (f.y1 - f.y0);
  const vg::Mesh mesh = vg::classic_layout(k);
  const vg::Scene scene(mesh);
  vg::NodeGridOptions nopt;
  nopt.spacing = spacing;
  nopt.eye_height = eye;
  nopt.walkable = {"floor"};
  const vg::NodeSet nodes = vg::generate_nodes(scene, nopt);
  r.eyes = nodes.eyes;
  vg::VisibilityOptions vopt;
  vopt.sigmas = conds.all_sigmas;
  vopt.threads = ctx.threads;
  const vg::VisibilityResult all = vg::all_to_all(scene, r.eyes, vopt);
  r.pairs = all.pairs_total;
  const std::size_t n = r.eyes.size();
  r.degree.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    r.degree[i] = all.degree.at(i);
    r.x.push_back(r.eyes[i].x());
    r.y.push_back(r.eyes[i].y());
    r.z.push_back(r.eyes[i].z());
  }
  r.ss = all.sum;
  for (const auto& col : r.ss)
    for (std::size_t i = 0; i < n; ++i)
      if (col[i] > r.degree[i]) ++r.ss_above_degree;
  // Bottom-left corner node: smallest x + y (ties: smallest x).
  for (std::size_t i = 1; i < n; ++i) {
    const double a = r.x[i] + r.y[i], b = r.x[r.corner] + r.y[r.corner];
    if (a < b || (a == b && r.x[i] < r.x[r.corner])) r.corner = i;
  }
  vg::VisibilityOptions popt;
  popt.sigmas = conds.point_sigmas;
  popt.threads = ctx.threads;
  const vg::VisibilityResult point = vg::to_targets(scene, r.eyes, {r.eyes[r.corner]}, popt);
  r.corner_c = point.sum;
  r.seconds = seconds_since(t0);
  return r;
}

// Per-node data files (the figures are drawn from them).
void write_node_files(Context& ctx, const std::vector<LayoutRun>& runs, const LayoutConditions& conds) {
  for (const auto& r : runs) {
    std::vector<std::string> header = {"x", "y", "z", "degree"};
    std::vector<const std::vector<double>*> cols = {&r.x, &r.y, &r.z, &r.degree};
    for (std::size_t k = 0; k < conds.all.size(); ++k) {
      header.push_back("sum:" + conds.all[k].column_label());
      cols.push_back(&r.ss[k]);
    }
    for (std::size_t k = 0; k < conds.point.size(); ++k) {
      header.push_back("c:corner:" + conds.point[k].column_label());
      cols.push_back(&r.corner_c[k]);
    }
    write_data_csv(ctx, "layout" + std::to_string(r.index) + "_nodes.csv", header, cols);
  }
}

// Extremes of degree and clear-weather S_S over the five layouts.
struct ClearExtremes {
  double max_deg = 0, min_deg = 1e300, max_ss = 0, min_ss = 1e300;
  int most_edges = 0, most_degree = 0;
};

// Degree and S_S in clear weather (all.front() is clear), per layout.
ClearExtremes degree_table(Context& ctx, Section& s, const std::vector<LayoutRun>& runs,
                           const std::vector<VgCondition>& all) {
  const std::size_t clear = 0;
  Table t{"layouts_degree", "Nodes, degree and clear-weather S_S (sigma = " + sig(all[clear].sigma) +
                                " 1/m) of the five layouts",
          {"layout", "name", "nodes", "2500 - obstacle area", "degree min", "degree max", "degree mean",
           "edges (sum deg / 2)", "S_S clear min", "S_S clear max", "max S_S / max deg", "min S_S / min deg",
           "nodes with S_S > degree (any condition)"},
          {},
          "Expected node count: 2500 cells of 1 m^2 minus the obstacles' footprint area (2424, 2000, 2400, "
          "2000, 2460 for layouts 0-4). The seed paper prints no node counts."};
  ClearExtremes ex;
  double best_edges = -1, best_degree = -1;
  for (const auto& r : runs) {
    const Range d = range_of(r.degree), c = range_of(r.ss[clear]);
    const double edges = std::accumulate(r.degree.begin(), r.degree.end(), 0.0) / 2;
    t.add_row({r.index, r.name, r.eyes.size(), 2500 - r.obstacle_area, d.min, d.max, Cell(d.mean, 6), edges,
               Cell(c.min, 6), Cell(c.max, 6), Cell(c.max / d.max, 5), Cell(c.min / d.min, 5), r.ss_above_degree});
    const std::string p = "layouts." + std::to_string(r.index) + ".";
    ctx.set(p + "nodes", static_cast<double>(r.eyes.size()));
    ctx.set(p + "degree_min", d.min);
    ctx.set(p + "degree_max", d.max);
    ctx.set(p + "degree_mean", d.mean);
    ctx.set(p + "edges", edges);
    ctx.set(p + "ss_above_degree", static_cast<double>(r.ss_above_degree));
    ctx.set(p + "corner_x", r.x[r.corner]);
    ctx.set(p + "corner_y", r.y[r.corner]);
    for (std::size_t k = 0; k < all.size(); ++k) {
      const Range q = range_of(r.ss[k]);
      ctx.set(p + "ss_" + all[k].tag + "_min", q.min);
      ctx.set(p + "ss_" + all[k].tag + "_max", q.max);
    }
    if (edges > best_edges) best_edges = edges, ex.most_edges = r.index;
    if (d.max > best_degree) best_degree = d.max, ex.most_degree = r.index;
    ex.max_deg = std::max(ex.max_deg, d.max);
    ex.min_deg = std::min(ex.min_deg, d.min);
    ex.max_ss = std::max(ex.max_ss, c.max);
    ex.min_ss = std::min(ex.min_ss, c.min);
  }
  add_table(ctx, s, t);
  ctx.set("layouts.most_edges_index", ex.most_edges);
  ctx.set("layouts.max_degree", ex.max_deg);
  ctx.set("layouts.min_degree", ex.min_deg);
  ctx.set("layouts.max_ss_clear", ex.max_ss);
  ctx.set("layouts.min_ss_clear", ex.min_ss);
  for (const auto& r : runs)
    s.data("layout" + std::to_string(r.index) + "_nodes.csv",
           "per-node x, y, z, degree, S_S per condition and C to the bottom-left corner node, layout " +
               std::to_string(r.index) + " (" + r.name + ")");
  return ex;
}

// The seed's clear-weather statements against this run.
void seed_comparison(Context& ctx, Section& s, const std::vector<LayoutRun>& runs, const ClearExtremes& ex) {
  Table cmp{"layouts_vs_seed", "The seed's clear-weather statements against this run",
            {"quantity", "seed paper", "this run", "agreement"},
            {},
            "Seed paper, Sec. Results / Visibility Graph Case: Fig. count caption (third layout has the most "
            "edge connections) and the text of Fig. vg_clear (max 2526 vs 2536, min 359 vs 360)."};
  const bool third = ex.most_edges == 2;
  cmp.add_row({"layout with the most connections (total edges)", "third (index 2)",
               "index " + std::to_string(ex.most_edges) + " (" + runs[ex.most_edges].name + ")", third ? "same" : "differs"});
  cmp.add_row({"layout with the highest node degree", "-",
               "index " + std::to_string(ex.most_degree) + " (" + runs[ex.most_degree].name + ")", "-"});
  cmp.add_row({"max degree over the five layouts", 2536.0, ex.max_deg, "see below"});
  cmp.add_row({"max clear S_S over the five layouts", 2526.0, ex.max_ss, "see below"});
  cmp.add_row({"ratio max S_S / max degree", Cell(2526.0 / 2536.0, 5), Cell(ex.max_ss / ex.max_deg, 5),
               format_number(100 * (ex.max_ss / ex.max_deg - 2526.0 / 2536.0), 2) + " percentage points"});
  cmp.add_row({"min degree over the five layouts", 360.0, ex.min_deg, "see below"});
  cmp.add_row({"min clear S_S over the five layouts", 359.0, ex.min_ss, "see below"});
  cmp.add_row({"ratio min S_S / min degree", Cell(359.0 / 360.0, 5), Cell(ex.min_ss / ex.min_deg, 5),
               format_number(100 * (ex.min_ss / ex.min_deg - 359.0 / 360.0), 2) + " percentage points"});
  add_table(ctx, s, cmp);
  ctx.set("layouts.ratio_max", ex.max_ss / ex.max_deg);
  ctx.set("layouts.ratio_min", ex.min_ss / ex.min_deg);
  if (third)
    s.agree("the third layout (single block) has the most connections, as in the seed's Fig. count.");
  else
    s.disagree("the layout with the most connections here is index " + std::to_string(ex.most_edges) +
               ", not the third as in the seed's Fig. count.");
  s.agree("S_S is close to degree in clear weather: max S_S / max degree = " + sig(ex.max_ss / ex.max_deg, 5) +
          " (seed 2526/2536 = " + sig(2526.0 / 2536.0, 5) + "), min ratio " + sig(ex.min_ss / ex.min_deg, 5) +
          " (seed 359/360 = " + sig(359.0 / 360.0, 5) + "). No node has S_S > degree in any condition (" +
          std::to_string(std::accumulate(runs.begin(), runs.end(), std::size_t{0},
                                         [](std::size_t a, const LayoutRun& r) { return a + r.ss_above_degree; })) +
          " violations).");
  s.disagree("the absolute extremes differ: our maximum degree is " + sig(ex.max_deg) +
             ", while a 50 x 50 m floor sampled at 1 m cell centres has at most 2500 nodes, so the seed's 2536 "
             "cannot come from this grid; the seed's node grid must have held more points (e.g. a lattice "
             "including the 51st row/column, 51 x 51 = 2601 points). Its exact sampling is not stated, so the "
             "absolute degree values are not reproducible; the ratios S_S/degree are.");
}

// S_S range of each layout under each condition.
void weather_table(Context& ctx, Section& s, const std::vector<LayoutRun>& runs,
                   const std::vector<VgCondition>& all) {
  Table w{"layouts_weather", "S_S range (min - max) of each layout under each condition",
          {"layout", "name"}, {}, ""};
  for (const auto& c : all) w.header.push_back(c.label + " [sigma " + sig(c.sigma, 4) + " 1/m]");
  for (const auto& r : runs) {
    std::vector<Cell> row = {r.index, r.name};
    for (std::size_t k = 0; k < all.size(); ++k) {
      const Range q = range_of(r.ss[k]);
      row.push_back(format_number(q.min, 4) + " - " + format_number(q.max, 4));
    }
    w.add_row(row);
  }
  add_table(ctx, s, w);
}

// The single block's S_S ranges in rain and snow against the seed's, per
// convention; returns the convention that comes closest.
std::string single_block_comparison(Context& ctx, Section& s, const std::vector<LayoutRun>& runs,
                                    const std::vector<VgCondition>& all) {
  Table sb{"layouts_single_block_vs_seed",
           "Single-block layout (index 2): S_S range under rain 8 mm/h and dry snow 4 mm/h against the seed",
           {"condition", "convention", "sigma [1/m]", "S_S min", "S_S max", "seed min", "seed max",
            "min rel. diff", "max rel. diff"},
           {},
           "Seed paper, Sec. Results, discussion of Fig. vg_weather: 'the middle case (single box) ... S_S range "
           "of 696-2271' in rain and '411-1240' in snow."};
  const LayoutRun& block = runs[2];
  struct SeedRange {
    const char* condition;
    double lo, hi;
  };
  // Our grid cannot hold the seed's node count (its max degree 2536 exceeds
  // our 2500 cells), so S_S is also compared normalised by the maximum degree:
  // the seed's 2536 is taken as the single block's maximum degree, since its
  // Fig. count says the third layout has the most connections.
  sb.header.push_back("our S_S max / our max degree");
  sb.header.push_back("seed S_S max / 2536");
  const double block_max_degree = range_of(block.degree).max;
  std::map<std::string, double> conv_err;
  for (const SeedRange pr : {SeedRange{"rain:8", 696, 2271}, SeedRange{"snow:dry:4", 411, 1240}}) {
    for (std::size_t k = 0; k < all.size(); ++k) {
      if (all[k].condition != pr.condition) continue;
      const Range q = range_of(block.ss[k]);
      const double e1 = q.min / pr.lo - 1, e2 = q.max / pr.hi - 1;
      const double ours_n = q.max / block_max_degree, seed_n = pr.hi / 2536.0;
      sb.add_row({all[k].label, all[k].convention, Cell(all[k].sigma, 5), Cell(q.min, 5),
                  Cell(q.max, 5), pr.lo, pr.hi, Cell(e1, 3), Cell(e2, 3), Cell(ours_n, 4), Cell(seed_n, 4)});
      ctx.set("layouts.2.ss_" + all[k].tag + "_relerr_max", e2);
      ctx.set("layouts.2.ss_" + all[k].tag + "_normalised_max", ours_n);
      conv_err[all[k].convention] += std::fabs(ours_n / seed_n - 1);
    }
  }
  std::string best_convention;
  double best_err = 1e300;
  for (const auto& [conv, err] : conv_err)
    if (err < best_err) best_err = err, best_convention = conv;
  add_table(ctx, s, sb);
  std::string others;
  for (const auto& [conv, err] : conv_err)
    if (conv != best_convention) others += ", against " + sig(err, 3) + " for '" + conv + "'";
  s.text("Which convention reproduces the seed's ranges: '" + best_convention +
         "' is closest: normalised by the maximum degree, the sum over rain and snow of |ours / seed - 1| is " +
         sig(best_err, 3) + others + ". Unnormalised values differ more because the seed's grid had more nodes (its "
         "max degree 2536 exceeds our 2500 cells), so its S_S values are larger by roughly the ratio of node counts.");
  ctx.closing->push_back(verdict(
      best_convention == "seed" ? "agree" : "disagree",
      "Single-block layout: S_S ranges in rain 8 mm/h and dry snow 4 mm/h (Fig. vg_single)",
      "closest with the '" + best_convention + "' reading of the power laws (normalised error " + sig(best_err, 3) +
          others + ")",
      best_convention == "seed"
          ? "Reproduced with the power laws read as 1/km, i.e. the seed's sigma values, not ITU-R P.1817's dB/km."
          : "The seed's ranges are not matched by the seed's own reading of the power laws."));
  return best_convention;
}

// Node maps of degree and S_S per condition (seed Figs. count, vg_clear, vg_weather).
void layout_figures(Section& s, const std::vector<LayoutRun>& runs, const std::vector<VgCondition>& all) {
  auto panels = [&](const std::string& column, const std::string& title_suffix, bool with_corner) {
    nlohmann::json ps = nlohmann::json::array();
    for (const auto& r : runs) {
      nlohmann::json p = {{"csv", "layout" + std::to_string(r.index) + "_nodes.csv"},
                          {"value", column},
                          {"title", std::to_string(r.index) + " " + r.name + title_suffix}};
      if (with_corner) p["markers"] = nlohmann::json::array({{{"x", r.x[r.corner]}, {"y", r.y[r.corner]}, {"label", ""}}});
      ps.push_back(p);
    }
    return ps;
  };
  s.figure({"layouts_degree_own", "Degree of each node, each layout on its own colour scale (seed Fig. count a).",
            {{"kind", "node_maps"}, {"panels", panels("degree", "", false)}, {"ncols", 5}}});
  s.figure({"layouts_degree_common",
            "Degree of each node, one common colour scale (seed Fig. count b: the third layout has the most "
            "connections).",
            {{"kind", "node_maps"}, {"panels", panels("degree", "", false)}, {"ncols", 5}, {"common_scale", true},
             {"colorbar", "degree"}}});
  s.figure({"layouts_ss_clear", "S_S in clear weather (sigma = " + sig(all[0].sigma) +
                                    " 1/m), common colour scale: indistinguishable from the degree (seed Fig. vg_clear).",
            {{"kind", "node_maps"}, {"panels", panels("sum:" + all[0].column_label(), "", false)}, {"ncols", 5},
             {"common_scale", true}, {"colorbar", "S_S clear"}}});
  for (std::size_t k = 1; k < all.size(); ++k) {
    s.figure({"layouts_ss_" + all[k].tag,
              "S_S under " + all[k].label + ", sigma = " + sig(all[k].sigma, 4) +
                  " 1/m, common colour scale (seed Fig. vg_weather).",
              {{"kind", "node_maps"}, {"panels", panels("sum:" + all[k].column_label(), "", false)}, {"ncols", 5},
               {"common_scale", true}, {"colorbar", "S_S"}}});
  }
}

// Contrast ratio C of every node to the bottom-left node (seed Fig. vg_ab).
void single_point_analysis(Context& ctx, Section& s, const std::vector<LayoutRun>& runs,
                           const std::vector<VgCondition>& point) {
  Table sp{"layouts_single_point", "Single-point analysis: contrast ratio C of every node to the bottom-left node",
           {"layout", "corner node x", "corner node y", "nodes seeing it"}, {}, ""};
  for (const auto& c : point) sp.header.push_back("C range, " + c.label);
  nlohmann::json sp_panels = nlohmann::json::array();
  for (const auto& r : runs) {
    std::size_t seeing = 0;
    for (double c : r.corner_c[0]) seeing += c > 0;
    std::vector<Cell> row = {r.index, r.x[r.corner], r.y[r.corner], seeing};
    for (std::size_t k = 0; k < point.size(); ++k) {
      double lo = 1e300, hi = 0;
      for (double c : r.corner_c[k])
        if (c > 0) lo = std::min(lo, c), hi = std::max(hi, c);
      row.push_back(seeing ? format_number(lo, 4) + " - " + format_number(hi, 4) : std::string("-"));
    }
    sp.add_row(row);
    ctx.set("layouts." + std::to_string(r.index) + ".corner_seen_by", static_cast<double>(seeing));
  }
  for (std::size_t k = 0; k < point.size(); ++k)
    for (const auto& r : runs)
      sp_panels.push_back({{"csv", "layout" + std::to_string(r.index) + "_nodes.csv"},
                           {"value", "c:corner:" + point[k].column_label()},
                           {"title", std::to_string(r.index) + ": " + point[k].short_label},
                           {"markers", nlohmann::json::array({{{"x", r.x[r.corner]}, {"y", r.y[r.corner]}}})}});
  add_table(ctx, s, sp);
  s.text("C = exp(-sigma d) when the node sees the corner node, 0 when it does not (and 0 for the corner node "
         "itself). In clear weather the map is nearly binary, as the seed says of its Fig. vg_ab.");
  s.figure({"layouts_single_point",
            "Contrast ratio C of every node to the bottom-left node, scale 0 (dark) to 1 (yellow), rows: " +
                [&] {
                  std::string l;
                  for (auto& c : point) l += (l.empty() ? "" : "; ") + c.label;
                  return l;
                }() + " (seed Fig. vg_ab).",
            {{"kind", "node_maps"}, {"panels", sp_panels}, {"ncols", 5}, {"common_scale", true}, {"vmin", 0.0},
             {"vmax", 1.0}, {"colorbar", "C"}, {"panel_size", 2.4}}});
}

void layouts_summary(Context& ctx, Section& s, const std::vector<LayoutRun>& runs, const ClearExtremes& ex,
                     const std::string& best_convention) {
  double secs = 0;
  std::uint64_t pairs = 0;
  for (const auto& r : runs) secs += r.seconds, pairs += r.pairs;
  s.summary.push_back("nodes " + [&] {
    std::string l;
    for (auto& r : runs) l += (l.empty() ? "" : "/") + std::to_string(r.eyes.size());
    return l;
  }() + " (expected 2424/2000/2400/2000/2460); most connections: layout " + std::to_string(ex.most_edges) +
                      " (seed: third)");
  s.summary.push_back("clear: max S_S/max deg " + sig(ex.max_ss, 6) + "/" + sig(ex.max_deg) + " = " +
                      sig(ex.max_ss / ex.max_deg, 4) + " (seed 2526/2536 = 0.9961); min " + sig(ex.min_ss, 6) + "/" +
                      sig(ex.min_deg) + " (seed 359/360)");
  s.summary.push_back("single block S_S range closest to the seed's with convention '" + best_convention + "'");
  s.text("Timing: " + std::to_string(pairs) + " pairs in " + sig(secs, 3) + " s for the five layouts (all-to-all "
         "plus single point), " + std::to_string(ctx.threads) + " thread(s).");
}

}  // namespace

void section_layouts(Context& ctx, Section& s, const SeedConditions& seed) {
  const LayoutConditions conds = layout_conditions(seed);
  s.text("Each layout is generated as code (visgraph/generators.hpp: floor [0,50]^2 m at z = 0, obstacles 10 m "
         "tall), nodes on a 1 m grid of cell centres over the floor (rays cast down; cells under an obstacle are "
         "dropped), eyes 1.7 m above the floor, as in the seed (Sec. Comparative Models and Results). Every "
         "unordered pair is cast once with Embree; degree, S_S = sum of C = exp(-sigma d) over visible partners. "
         "No pruning here: every score is exact.");
  std::vector<LayoutRun> runs;
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) runs.push_back(run_layout(ctx, k, conds));
  write_node_files(ctx, runs, conds);
  const ClearExtremes ex = degree_table(ctx, s, runs, conds.all);
  seed_comparison(ctx, s, runs, ex);
  weather_table(ctx, s, runs, conds.all);
  const std::string best_convention = single_block_comparison(ctx, s, runs, conds.all);
  layout_figures(s, runs, conds.all);
  single_point_analysis(ctx, s, runs, conds.point);
  layouts_summary(ctx, s, runs, ex, best_convention);
}

}  // namespace attenuvis::validation::detail
