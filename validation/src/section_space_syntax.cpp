// Section "Space syntax in weather": the five layouts' visual integration and
// clustering under clear weather, rain, fog and snow (the seed's Fig.
// vg_weather in the measures of visibility graph analysis), and the city's
// integration in clear weather and fog with the measures at P1-P3
// (visgraph/space_syntax.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "attenuvis/visgraph/generators.hpp"
#include "attenuvis/visgraph/layouts.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "attenuvis/visgraph/scene_spec.hpp"
#include "attenuvis/visgraph/space_syntax.hpp"
#include "attenuvis/visgraph/work_estimate.hpp"
#include "sections.hpp"

namespace attenuvis::validation::detail {

namespace {
namespace vg = attenuvis::visgraph;

// On the 50 m layouts every weather's 2 % range exceeds the layout, so the
// graphs are shown at half the clear contrast (the seed's legible sign).
constexpr double kLayoutContrast = 0.5;
const char* const kMeasures = "connectivity,clustering,control,controllability,mean-depth,integration,entropy,component";

// The seed's Fig. vg_weather conditions with the seed's own sigma (its
// reading of the power laws), as its figure uses them.
std::vector<VgCondition> seed_weathers(const SeedConditions& seed) {
  std::vector<VgCondition> out;
  for (const char* name : {"clear", "rain:8", "fog:advection", "snow:dry:4"})
    for (const VgCondition& c : vg_conditions(seed, name))
      if (c.convention != "itu") out.push_back(c);
  return out;
}

std::vector<double> sigmas_of(const std::vector<VgCondition>& conds) {
  std::vector<double> s;
  for (const VgCondition& c : conds) s.push_back(c.sigma);
  return s;
}

vg::SpaceSyntaxOptions syntax_options(const std::vector<VgCondition>& conds, double eps, int threads) {
  vg::SpaceSyntaxOptions o;
  o.sigmas = sigmas_of(conds);
  o.contrast_threshold = eps;
  o.measures = vg::parse_measures(kMeasures);
  o.threads = threads;
  return o;
}

// -1 (undefined: a node alone, or seeing all of its component) left out of
// the maps and the means.
std::vector<double> defined(const std::vector<double>& v) {
  std::vector<double> out(v);
  for (double& x : out)
    if (x == -1.0) x = std::numeric_limits<double>::quiet_NaN();
  return out;
}

double mean_defined(const std::vector<double>& v) {
  double sum = 0;
  std::size_t n = 0;
  for (double x : v)
    if (x != -1.0 && std::isfinite(x)) sum += x, ++n;
  return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

struct LayoutSyntax {
  int index = 0;
  std::string name;
  std::vector<double> x, y, z;
  vg::SpaceSyntaxResult r;
  double seconds = 0;
};

// The seed's 1 m grid; 2 m in quick mode.
double layout_spacing(const Context& ctx) { return ctx.options.quick ? 2.0 : 1.0; }

LayoutSyntax layout_syntax(Context& ctx, int k, const std::vector<VgCondition>& conds) {
  ctx.step("space syntax", "layout " + std::to_string(k));
  LayoutSyntax out;
  out.index = k;
  out.name = vg::classic_layout_name(k);
  const vg::Scene scene(vg::classic_layout(k));
  vg::NodeGridOptions grid;
  grid.spacing = layout_spacing(ctx);
  grid.eye_height = 1.7;
  grid.walkable = vg::classic_layout_walkable_groups();
  const std::vector<Eigen::Vector3d> eyes = vg::generate_nodes(scene, grid).eyes;
  for (const auto& e : eyes) out.x.push_back(e.x()), out.y.push_back(e.y()), out.z.push_back(e.z());
  vg::VisibilityOptions pass;
  pass.sigmas = sigmas_of(conds);
  pass.threads = ctx.threads;
  const auto t0 = std::chrono::steady_clock::now();
  out.r = vg::space_syntax(scene, eyes, pass, syntax_options(conds, kLayoutContrast, ctx.threads)).measures;
  out.seconds = seconds_since(t0);
  return out;
}

void write_layout_files(Context& ctx, Section& s, const std::vector<LayoutSyntax>& runs,
                        const std::vector<VgCondition>& conds) {
  for (const LayoutSyntax& l : runs) {
    std::vector<std::string> header = {"x", "y", "z"};
    std::vector<std::vector<double>> kept;
    for (const char* m : {"integration_hh", "clustering", "mean_depth", "connectivity"})
      for (std::size_t k = 0; k < conds.size(); ++k) {
        header.push_back(std::string(m) + ":" + conds[k].column_label());
        kept.push_back(defined(l.r.values(m, k)));
      }
    std::vector<const std::vector<double>*> cols = {&l.x, &l.y, &l.z};
    for (const auto& c : kept) cols.push_back(&c);
    const std::string file = "layout" + std::to_string(l.index) + "_space_syntax.csv";
    write_data_csv(ctx, file, header, cols);
    s.data(file, "per-node integration [HH], clustering, mean depth and connectivity per weather at contrast " +
                     format_number(kLayoutContrast, 2) + " (blank where depthmapX writes -1), layout " +
                     std::to_string(l.index) + " (" + l.name + ")");
  }
}

void layouts_table(Context& ctx, Section& s, const std::vector<LayoutSyntax>& runs,
                   const std::vector<VgCondition>& conds) {
  Table t{"space_syntax_layouts",
          "The five layouts at " + format_number(layout_spacing(ctx), 2) + " m, each weather's graph at contrast " +
              format_number(kLayoutContrast, 2) +
              ": lines of sight kept, components, and the means of visual integration [HH], clustering and mean depth",
          {"layout", "name", "weather", "sigma [1/m]", "range at this contrast [m]", "lines of sight", "components",
           "mean integration [HH]", "mean clustering", "mean mean depth", "same graph as"},
          {},
          "Definitions: visgraph/space_syntax.hpp (Turner et al. 2001; Hillier & Hanson 1984; depthmapX). Means "
          "over the nodes where the measure is defined."};
  for (const LayoutSyntax& l : runs)
    for (std::size_t k = 0; k < conds.size(); ++k) {
      const int same = l.r.same_graph_as[k];
      const double mi = mean_defined(l.r.values("integration_hh", k));
      t.add_row({l.index, l.name, conds[k].short_label, Cell(conds[k].sigma, 4),
                 Cell(std::log(1.0 / kLayoutContrast) / conds[k].sigma, 4), l.r.edges[k], l.r.components[k],
                 Cell(mi, 5), Cell(mean_defined(l.r.values("clustering", k)), 5),
                 Cell(mean_defined(l.r.values("mean_depth", k)), 5),
                 same >= 0 ? conds[static_cast<std::size_t>(same)].short_label : std::string("-")});
      ctx.set("space_syntax.layout" + std::to_string(l.index) + "." + conds[k].tag + ".integration_hh_mean", mi);
      ctx.set("space_syntax.layout" + std::to_string(l.index) + "." + conds[k].tag + ".lines",
              static_cast<double>(l.r.edges[k]));
    }
  add_table(ctx, s, t);
}

void layout_figures(Section& s, const std::vector<LayoutSyntax>& runs, const std::vector<VgCondition>& conds) {
  const auto maps = [&](const std::string& measure) {
    nlohmann::json panels = nlohmann::json::array();
    for (const LayoutSyntax& l : runs)
      for (const VgCondition& c : conds)
        panels.push_back({{"csv", "layout" + std::to_string(l.index) + "_space_syntax.csv"},
                          {"value", measure + ":" + c.column_label()},
                          {"title", std::to_string(l.index) + " " + l.name + ", " + c.short_label}});
    return panels;
  };
  s.figure({"space_syntax_integration",
            "Visual integration [HH] of each layout (rows) in clear weather, rain 8 mm/h, heavy advection fog and "
            "dry snow 4 mm/h (columns; the seed's sigma), each weather's graph keeping the lines whose contrast is "
            "at least half the clear one; one logarithmic colour scale (the single block's open floor integrates "
            "several times more than the others). Blank: undefined (depthmapX's -1).",
            {{"kind", "node_maps"}, {"panels", maps("integration_hh")}, {"ncols", conds.size()},
             {"common_scale", true}, {"log", true}, {"colorbar", "visual integration [HH]"}, {"panel_size", 2.3}}});
  s.figure({"space_syntax_clustering",
            "Visual clustering coefficient, as above (one colour scale, 0 to 1).",
            {{"kind", "node_maps"}, {"panels", maps("clustering")}, {"ncols", conds.size()}, {"common_scale", true},
             {"vmin", 0.0}, {"vmax", 1.0}, {"colorbar", "visual clustering coefficient"}, {"panel_size", 2.3}}});
}

// ---- The city ------------------------------------------------------------------
void city_table(Context& ctx, Section& s, const CityLines& city, const vg::SpaceSyntaxResult& r,
                const std::vector<VgCondition>& conds) {
  Table t{"space_syntax_city_points",
          "The measures at P1, P2, P3 (the city section's points) in each weather's graph at contrast 0.02",
          {"point", "weather", "connectivity", "integration [HH]", "mean depth", "node count", "clustering", "control",
           "controllability", "entropy", "component size"},
          {},
          "Definitions: visgraph/space_syntax.hpp; -1 where depthmapX writes -1."};
  const char* measures[] = {"connectivity", "integration_hh", "mean_depth", "node_count", "clustering",
                            "control",      "controllability", "entropy",  "component_size"};
  for (std::size_t p = 0; p < city.points.size(); ++p)
    for (std::size_t k = 0; k < conds.size(); ++k) {
      std::vector<Cell> row = {city.point_names[p], conds[k].short_label};
      for (const char* m : measures) {
        const double v = r.values(m, k)[city.points[p]];
        row.push_back(Cell(v, 6));
        ctx.set("space_syntax.city." + city.point_names[p] + "." + conds[k].tag + "." + m, v);
      }
      t.add_row(row);
    }
  add_table(ctx, s, t);
}

void city_figure(Context& ctx, Section& s, const CityLines& city, const vg::SpaceSyntaxResult& r,
                 const std::vector<VgCondition>& conds) {
  std::vector<double> x, y, z;
  for (const auto& e : city.eyes) x.push_back(e.x()), y.push_back(e.y()), z.push_back(e.z());
  std::vector<std::string> header = {"x", "y", "z"};
  std::vector<std::vector<double>> kept;
  for (const char* m : {"integration_hh", "clustering", "connectivity", "component_size"})
    for (std::size_t k = 0; k < conds.size(); ++k) {
      header.push_back(std::string(m) + ":" + conds[k].column_label());
      kept.push_back(defined(r.values(m, k)));
    }
  std::vector<const std::vector<double>*> cols = {&x, &y, &z};
  for (const auto& c : kept) cols.push_back(&c);
  write_data_csv(ctx, "city_space_syntax.csv", header, cols);
  s.data("city_space_syntax.csv", "per-node integration [HH], clustering, connectivity and component size of the "
                                  "city in clear weather and fog at contrast 0.02 (blank where depthmapX writes -1)");
  nlohmann::json markers = nlohmann::json::array();
  const char* symbol[3] = {"o", "s", "^"};
  for (std::size_t p = 0; p < city.points.size() && p < 3; ++p)
    markers.push_back({{"x", x[city.points[p]]}, {"y", y[city.points[p]]}, {"label", city.point_names[p]},
                       {"marker", symbol[p]}});
  nlohmann::json panels = nlohmann::json::array();
  for (const VgCondition& c : conds)
    panels.push_back({{"csv", "city_space_syntax.csv"}, {"value", "integration_hh:" + c.column_label()},
                      {"title", c.short_label}, {"markers", markers}});
  s.figure({"space_syntax_city",
            "Visual integration [HH] of the city in clear weather and in heavy advection fog, each weather's graph "
            "at Koschmieder's contrast 0.02 (each panel its own colour scale: fog leaves local graphs with far "
            "fewer nodes), with P1 (circle), P2 (square) and P3 (triangle).",
            {{"kind", "node_maps"}, {"panels", panels}, {"ncols", conds.size()}, {"cmap", "jet"}, {"panel_size", 4.6},
             {"dpi", 120}}});
  (void)ctx;
}

void city_syntax(Context& ctx, Section& s, const CityLines& city, const SeedConditions& seed) {
  std::vector<VgCondition> conds;
  for (const char* name : {"clear", "fog:advection"})
    for (const VgCondition& c : vg_conditions(seed, name)) conds.push_back(c);
  ctx.step("space syntax", "the city's " + std::to_string(city.eyes.size()) + " nodes, clear and fog");
  const auto t0 = std::chrono::steady_clock::now();
  const vg::SpaceSyntaxResult r = vg::space_syntax(*city.graph, syntax_options(conds, vg::kKoschmiederContrast, ctx.threads));
  const double seconds = seconds_since(t0);
  s.text("The city (the city section's " + std::to_string(city.eyes.size()) + " nodes and its " +
         std::to_string(city.graph->edges()) + " lines of sight, held as " + (r.bit_rows ? "bit rows" : "CSR lists") +
         "): every measure above in clear weather and in heavy advection fog at Koschmieder's contrast 0.02, in " +
         sig(seconds, 3) + " s on " + std::to_string(ctx.threads) + " thread(s). Fog keeps " +
         std::to_string(r.edges[1]) + " of the lines (" + sig(100.0 * r.edges[1] / std::max<double>(1, r.edges[0]), 3) +
         " %) and breaks the city into " + std::to_string(r.components[1]) + " components (clear: " +
         std::to_string(r.components[0]) + ").");
  ctx.set("space_syntax.city.seconds", seconds);
  ctx.set("space_syntax.city.components_fog", static_cast<double>(r.components[1]));
  ctx.set("space_syntax.city.lines_fog", static_cast<double>(r.edges[1]));
  city_table(ctx, s, city, r, conds);
  city_figure(ctx, s, city, r, conds);
  s.summary.push_back("city: " + std::to_string(city.eyes.size()) + " nodes in " + sig(seconds, 3) +
                      " s; fog at 0.02 keeps " + sig(100.0 * r.edges[1] / std::max<double>(1, r.edges[0]), 3) +
                      " % of the lines, " + std::to_string(r.components[1]) + " components");
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double sa = 0, sb = 0, n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != -1.0 && b[i] != -1.0) sa += a[i], sb += b[i], ++n;
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  const double ma = sa / n, mb = sb / n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != -1.0 && b[i] != -1.0) ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma), bb += (b[i] - mb) * (b[i] - mb);
  return ab / std::sqrt(aa * bb);
}

// Whether rain left every layout's graph as the clear one, said from the results.
std::string rain_sentence(const std::vector<LayoutSyntax>& runs, const std::vector<VgCondition>& conds) {
  for (std::size_t k = 0; k < conds.size(); ++k) {
    if (conds[k].condition != "rain:8") continue;
    bool all_clear = true;
    for (const LayoutSyntax& l : runs) all_clear = all_clear && l.r.same_graph_as[k] == 0;
    return all_clear ? " Rain 8 mm/h keeps every line of the five layouts at this contrast (its range, " +
                           sig(std::log(2.0) / conds[k].sigma, 3) + " m, exceeds their diagonal), so its maps are "
                           "the clear ones."
                     : " Rain 8 mm/h removes some lines too (its range is " + sig(std::log(2.0) / conds[k].sigma, 3) +
                           " m).";
  }
  return "";
}

// What changes, in numbers computed here.
void what_changes(Context& ctx, Section& s, const std::vector<LayoutSyntax>& runs, const std::vector<VgCondition>& conds) {
  std::size_t fog_k = 0;
  for (std::size_t k = 0; k < conds.size(); ++k)
    if (conds[k].condition == "fog:advection") fog_k = k;
  double clear = 0, fog = 0, cl_clear = 0, cl_fog = 0, r = 0;
  const double n = static_cast<double>(runs.size());
  for (const LayoutSyntax& l : runs) {
    clear += mean_defined(l.r.values("integration_hh", 0)) / n;
    fog += mean_defined(l.r.values("integration_hh", fog_k)) / n;
    cl_clear += mean_defined(l.r.values("clustering", 0)) / n;
    cl_fog += mean_defined(l.r.values("clustering", fog_k)) / n;
    r += correlation(l.r.values("integration_hh", 0), l.r.values("integration_hh", fog_k)) / n;
  }
  ctx.set("space_syntax.layouts.integration_clear_mean", clear);
  ctx.set("space_syntax.layouts.integration_fog_mean", fog);
  ctx.set("space_syntax.layouts.integration_clear_fog_correlation", r);
  s.text("What changes: at half the clear contrast fog keeps only the lines shorter than " +
         sig(std::log(2.0) / conds[fog_k].sigma, 3) + " m, so each node's visual neighbourhood shrinks to its "
         "surroundings. Over the five layouts the mean visual integration [HH] goes from " + sig(clear, 3) +
         " in clear weather to " + sig(fog, 3) + " in fog, the mean clustering from " + sig(cl_clear, 3) + " to " +
         sig(cl_fog, 3) + ", and the correlation between a layout's clear and fog integration maps is " + sig(r, 2) +
         " on average: fog does not scale the map, it redraws it." + rain_sentence(runs, conds));
}
}  // namespace

void section_space_syntax(Context& ctx, Section& s, const SeedConditions& seed, CityLines& city) {
  const std::vector<VgCondition> conds = seed_weathers(seed);
  s.text("The measures of visibility graph analysis (VGA) as depthmapX computes them (connectivity, visual "
         "clustering, control, controllability, mean depth, integration [HH], entropy; definitions and sources in "
         "visgraph/space_syntax.hpp and the guide docs/guide/space-syntax.md), computed exactly on attenuvis's lines "
         "of sight, and weather entering through each weather's graph: the lines whose contrast exp(-sigma d) is at "
         "least a threshold. On the 50 m layouts every weather's 2 % (Koschmieder) range is longer than the layout "
         "(fog: " + sig(std::log(50.0) / conds[2].sigma, 3) + " m), so at 0.02 every weather's graph is the clear "
         "one; the layouts are therefore shown at contrast 0.5, half the clear contrast (the seed's example of a "
         "sign that is still legible), and the city at 0.02. The seed's own sigma values are used (rain " +
         sig(conds[1].sigma, 3) + ", fog " + sig(conds[2].sigma, 3) + ", snow " + sig(conds[3].sigma, 3) + " 1/m).");
  std::vector<LayoutSyntax> runs;
  double seconds = 0;
  for (int k = 0; k < vg::kClassicLayoutCount; ++k) {
    runs.push_back(layout_syntax(ctx, k, conds));
    seconds += runs.back().seconds;
  }
  write_layout_files(ctx, s, runs, conds);
  layouts_table(ctx, s, runs, conds);
  layout_figures(s, runs, conds);
  what_changes(ctx, s, runs, conds);
  s.summary.push_back("five layouts at " + sig(layout_spacing(ctx), 2) + " m, four weathers at contrast 0.5: pass and "
                      "measures " + sig(seconds, 3) + " s");
  ctx.set("space_syntax.layouts_seconds", seconds);
  if (city.graph) {
    city_syntax(ctx, s, city, seed);
    city.graph.reset();  // the city's lines of sight are not needed after this section
  }
}

}  // namespace attenuvis::validation::detail
