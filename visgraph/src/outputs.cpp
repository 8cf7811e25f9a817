// CSV, PLY, heatmap and JSON outputs of a visibility pass.
#include <attenuvis/visgraph/outputs.hpp>

#include <attenuvis/io/install_paths.hpp>
#include <attenuvis/io/number_text.hpp>
#include <attenuvis/io/shell.hpp>
#include <attenuvis/io/staged_file.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#ifndef ATTENUVIS_PYTHON
#define ATTENUVIS_PYTHON "/usr/bin/python3"
#endif
#ifndef ATTENUVIS_VG_HEATMAP_SCRIPT
#define ATTENUVIS_VG_HEATMAP_SCRIPT "vg_heatmap.py"
#endif

namespace attenuvis::visgraph {

namespace {
bool has_pruning(const VisibilityResult& r) {
  return r.prune_below > 0 && std::isfinite(r.pruning_radius);
}

// Viridis, sampled at 9 points (matplotlib's _viridis_data at 0, 1/8, ..., 1).
Eigen::Vector3d viridis(double t) {
  static const double map[9][3] = {{0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517},
                                   {0.253935, 0.265254, 0.529983}, {0.206756, 0.371758, 0.553117},
                                   {0.163625, 0.471133, 0.558148}, {0.127568, 0.566949, 0.550556},
                                   {0.134692, 0.658636, 0.517649}, {0.266941, 0.748751, 0.440573},
                                   {0.993248, 0.906157, 0.143936}};
  t = std::clamp(t, 0.0, 1.0) * 8.0;
  const int i = std::min(7, static_cast<int>(t));
  const double f = t - i;
  return (1 - f) * Eigen::Vector3d(map[i][0], map[i][1], map[i][2]) +
         f * Eigen::Vector3d(map[i + 1][0], map[i + 1][1], map[i + 1][2]);
}
}  // namespace

std::vector<std::string> score_columns(const ScoreTable& table) {
  const VisibilityResult& r = *table.result;
  std::vector<std::string> columns = {"x", "y", "z"};
  if (r.degree_exact) columns.push_back("degree");
  // Per condition its sum and (when the degree is exact) its average, side by
  // side, so that a reader compares S_S and S_A of one condition at a glance:
  // x,y,z,degree,sum:A,avg:A,sum:B,avg:B,... (README).
  for (const std::string& label : table.labels) {
    columns.push_back("sum:" + label);
    if (r.degree_exact) columns.push_back("avg:" + label);
  }
  if (!r.mean_distance.empty()) {
    columns.push_back("mean_distance");
    columns.push_back("max_distance");
  }
  if (has_pruning(r)) columns.push_back("sum_error_bound");
  for (const NodeColumn& c : table.extra) columns.push_back(c.name);
  return columns;
}

std::vector<NodeColumn> space_syntax_columns(const SpaceSyntaxResult& result, const std::vector<std::string>& labels) {
  std::vector<NodeColumn> columns;
  for (const SpaceSyntaxColumn& c : result.columns)
    columns.push_back({c.measure + ":" + labels.at(c.condition), &c.values});
  return columns;
}

std::vector<double> score_values(const ScoreTable& table, const std::string& column) {
  const VisibilityResult& r = *table.result;
  const std::size_t N = r.nodes;
  std::vector<double> v(N);
  const std::vector<std::string> columns = score_columns(table);
  if (std::find(columns.begin(), columns.end(), column) == columns.end() || column == "x" || column == "y" ||
      column == "z") {
    std::string list;
    for (std::size_t c = 3; c < columns.size(); ++c) list += (list.empty() ? "" : ", ") + columns[c];
    throw std::invalid_argument("no score column '" + column + "' (available: " + list + ")");
  }
  for (const NodeColumn& c : table.extra)
    if (column == c.name) return *c.values;
  for (std::size_t k = 0; k < table.labels.size(); ++k) {
    if (column == "sum:" + table.labels[k]) {
      for (std::size_t i = 0; i < N; ++i) v[i] = r.sum[k][i];
      return v;
    }
    if (column == "avg:" + table.labels[k]) {
      for (std::size_t i = 0; i < N; ++i) v[i] = r.average(k, i);
      return v;
    }
  }
  for (std::size_t i = 0; i < N; ++i) {
    if (column == "degree") v[i] = r.degree[i];
    else if (column == "mean_distance") v[i] = r.mean_distance[i];
    else if (column == "max_distance") v[i] = r.max_distance[i];
    else v[i] = r.sum_error_bound(i);
  }
  return v;
}

void write_csv(const std::string& path, const ScoreTable& table) {
  io::write_file_atomically(path, [&](std::ostream& out) { write_csv(out, table); });
}

void write_csv(std::ostream& out, const ScoreTable& table) {
  const std::vector<std::string> columns = score_columns(table);
  std::vector<std::vector<double>> values;
  for (std::size_t c = 3; c < columns.size(); ++c) values.push_back(score_values(table, columns[c]));
  {
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
    out << "\n";
    out.precision(std::numeric_limits<double>::max_digits10);
    for (std::size_t i = 0; i < table.result->nodes; ++i) {
      const Eigen::Vector3d& p = (*table.eyes)[i];
      out << p.x() << "," << p.y() << "," << p.z();
      for (const auto& column : values) {
        out << ",";
        if (std::isnan(column[i])) out << "nan";
        else out << column[i];
      }
      out << "\n";
    }
  }
}

void write_ply(const std::string& path, const ScoreTable& table, const std::string& column) {
  io::write_file_atomically(path, [&](std::ostream& out) { write_ply(out, table, column); });
}

void write_ply(std::ostream& out, const ScoreTable& table, const std::string& column) {
  const std::vector<double> v = score_values(table, column);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double x : v)
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  {
    out << "ply\nformat ascii 1.0\ncomment attenuvis visibility graph, coloured by " << column
        << " (viridis)\nelement vertex " << v.size()
        << "\nproperty double x\nproperty double y\nproperty double z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty double value\nend_header\n";
    out.precision(std::numeric_limits<double>::max_digits10);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Eigen::Vector3d& p = (*table.eyes)[i];
      Eigen::Vector3d rgb(0.5, 0.5, 0.5);
      if (std::isfinite(v[i])) rgb = viridis(hi > lo ? (v[i] - lo) / (hi - lo) : 0.5);
      out << p.x() << " " << p.y() << " " << p.z();
      for (int c = 0; c < 3; ++c) out << " " << static_cast<int>(std::lround(255 * rgb[c]));
      out << " " << (std::isnan(v[i]) ? 0.0 : v[i]) << "\n";
    }
  }
}

void write_heatmap(const std::string& png_path, const std::string& csv_path, const HeatmapOptions& options) {
  // The script writes the staged temporary; commit() renames it into place,
  // and a failure leaves neither a partial PNG nor the temporary behind.
  io::StagedFile png(png_path);
  draw_heatmap(png.temporary_path(), csv_path, options);
  png.commit();
}

void draw_heatmap(const std::string& png_path, const std::string& csv_path, const HeatmapOptions& options) {
  if (options.columns.empty()) throw std::invalid_argument("heatmap: no column to draw");
  std::string command = io::shell_quote(ATTENUVIS_PYTHON) + " " + io::shell_quote(io::installed_or_source("scripts/vg_heatmap.py", ATTENUVIS_VG_HEATMAP_SCRIPT)) + " " +
                        io::shell_quote(csv_path) + " " + io::shell_quote(png_path);
  for (const std::string& c : options.columns) command += " " + io::shell_quote(c);
  if (!options.title.empty()) command += " --title " + io::shell_quote(options.title);
  if (!options.crs.empty()) command += " --crs " + io::shell_quote(options.crs);
  std::unique_ptr<io::StagedFile> cells;
  if (!options.covered_cells.empty()) {
    // A scratch file beside the PNG, removed with its StagedFile (never committed).
    cells = std::make_unique<io::StagedFile>(png_path + ".covered.csv");
    std::string text = "x,y\n";
    for (const Eigen::Vector2d& c : options.covered_cells) text += io::shortest(c.x()) + "," + io::shortest(c.y()) + "\n";
    cells->write(text);
    command += " --footprints " + io::shell_quote(cells->temporary_path());
  }
  const int status = std::system(command.c_str());
  if (status != 0)
    throw std::runtime_error("heatmap: '" + command + "' failed (status " + std::to_string(status) + ")");
}

void write_heatmap(const std::string& png_path, const std::string& csv_path, const std::string& column,
                   const std::string& title) {
  HeatmapOptions options;
  options.columns = {column};
  options.title = title;
  write_heatmap(png_path, csv_path, options);
}

std::vector<std::string> default_heatmap_columns(const ScoreTable& table) {
  std::vector<std::string> columns;
  for (const std::string& label : table.labels) columns.push_back("sum:" + label);
  if (columns.empty()) columns.push_back("degree");
  return columns;
}

namespace {
using nlohmann::json;

// Where the nodes stand: the grid's counts, its rule, and the nodes per
// surface class or group (the 20 largest, the rest summed).
json node_grid_json(const NodeSet& g) {
  json grid = {{"cells", g.cells},
               {"nodes", g.eyes.size()},
               {"dropped_no_surface", g.no_surface},
               {"dropped_covered", g.covered},
               {"dropped_too_steep", g.too_steep},
               {"dropped_no_headroom", g.no_headroom}};
  json surfaces = json::object();
  std::size_t other = 0;
  for (std::size_t k = 0; k < g.by_surface.size(); ++k) {
    if (k < 20) surfaces[g.by_surface[k].name] = g.by_surface[k].nodes;
    else other += g.by_surface[k].nodes;
  }
  if (other) surfaces["(" + std::to_string(g.by_surface.size() - 20) + " others)"] = other;
  grid["rule"] = g.rule;
  grid["spacing_m"] = g.spacing;
  if (!g.spacing_rule.empty()) grid["spacing_rule"] = g.spacing_rule;
  grid["nodes_by_surface"] = surfaces;
  grid["elevated_nodes"] = g.elevated;
  grid["max_elevation_m"] = g.max_elevation;
  return grid;
}

// Each score column's range and mean over the nodes that have a value.
json scores_json(const ScoreTable& table) {
  json scores = json::object();
  const std::vector<std::string> columns = score_columns(table);
  for (std::size_t c = 3; c < columns.size(); ++c) {
    const std::vector<double> v = score_values(table, columns[c]);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
    std::size_t n = 0;
    for (double x : v)
      if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x), sum += x, ++n;
    scores[columns[c]] = n ? json{{"min", lo}, {"max", hi}, {"mean", sum / n}, {"nodes_with_value", n}}
                           : json{{"nodes_with_value", 0}};
  }
  return scores;
}

// The space-syntax graphs: threshold, radius, storage, and per condition its
// lines of sight, components and the condition whose graph it shares.
json space_syntax_json(const SpaceSyntaxResult& ss, const RunInfo& info) {
  json per_condition = json::array();
  for (std::size_t k = 0; k < ss.edges.size(); ++k) {
    const std::ptrdiff_t same = ss.same_graph_as[k];
    const bool shares = same >= 0 && static_cast<std::size_t>(same) < info.conditions.size();
    per_condition.push_back({{"label", k < info.conditions.size() ? info.conditions[k].label : std::to_string(k)},
                             {"lines_of_sight", ss.edges[k]},
                             {"components", ss.components[k]},
                             {"same_graph_as",
                              shares ? json(info.conditions[static_cast<std::size_t>(same)].label) : json(nullptr)}});
  }
  return {{"contrast_threshold", info.contrast_threshold},
          {"radius", info.radius > 0 ? json(info.radius) : json("n")},
          {"graph", ss.bit_rows ? "bit rows" : "CSR"},
          {"graph_bytes", ss.graph_bytes},
          {"seconds", ss.seconds},
          {"conditions", per_condition}};
}
}  // namespace

std::string summary_json(const ScoreTable& table, const RunInfo& info) {
  const VisibilityResult& r = *table.result;
  json j;
  j["scene"] = {{"source", info.scene}, {"report", info.scene_report}};
  if (!info.scene_format.empty()) j["scene"]["format"] = info.scene_format;
  if (!info.crs.empty()) j["scene"]["crs"] = info.crs;
  if (!info.ground.empty()) j["scene"]["ground"] = info.ground;
  if (!info.warnings.empty()) j["warnings"] = info.warnings;
  j["mode"] = info.mode;
  if (info.mode == "to-targets") j["targets"] = info.targets;
  j["nodes"] = r.nodes;
  if (info.grid) j["node_grid"] = node_grid_json(*info.grid);
  j["pairs"] = {{"considered", r.pairs_total},
                {"cast", r.pairs_cast},
                {"visible", r.pairs_visible},
                {"coincident_skipped", r.coincident_pairs},
                {"culled_in_sight", r.pairs_culled_visible},
                {"culled_blocked", r.pairs_culled_blocked},
                {"visible_fraction_of_considered",
                 r.pairs_total ? static_cast<double>(r.pairs_visible) / r.pairs_total : 0.0}};
  json conditions = json::array();
  for (const ConditionInfo& c : info.conditions)
    conditions.push_back({{"label", c.label},
                          {"sigma_per_m", c.sigma},
                          {"sigma_error_per_m", c.sigma_error},
                          {"units", "1/m"},
                          {"model", c.model},
                          {"convention", c.convention},
                          {"note", c.note}});
  j["conditions"] = conditions;
  if (info.wavelength_m > 0) j["wavelength_m"] = info.wavelength_m;
  j["scores"] = scores_json(table);
  double worst_bound = 0;
  for (std::size_t i = 0; i < r.nodes; ++i) worst_bound = std::max(worst_bound, r.sum_error_bound(i));
  j["pruning"] = {{"prune_below", r.prune_below},
                  {"radius_m", std::isfinite(r.pruning_radius) ? json(r.pruning_radius) : json(nullptr)},
                  {"degree_exact", r.degree_exact},
                  {"note", r.pruning_note},
                  {"max_sum_error_bound", worst_bound},
                  {"fixed_point_rounding_bound_per_partner", std::ldexp(1.0, -41)}};
  if (info.space_syntax) j["space_syntax"] = space_syntax_json(*info.space_syntax, info);
  j["threads"] = info.threads;
  j["time_s"] = {{"visibility", r.seconds}, {"culling", r.culling_seconds}, {"total", info.total_seconds}};
  j["pairs_per_s"] = r.seconds > 0 ? static_cast<double>(r.pairs_total) / r.seconds : 0.0;
  j["cast_pairs_per_s"] = r.seconds > 0 ? static_cast<double>(r.pairs_cast) / r.seconds : 0.0;
  return j.dump(2) + "\n";
}

}  // namespace attenuvis::visgraph
