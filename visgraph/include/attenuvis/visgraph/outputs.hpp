// Writing visibility results: CSV table, PLY point cloud, PNG heatmap, JSON
// summary.  Every file is written atomically (a temporary file in the same
// directory, renamed into place), so a failed run leaves no partial output.
// Positions are always in the world (original, un-recentred) frame.
#pragma once

#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/space_syntax.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <Eigen/Core>

#include <iosfwd>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// A column of per-node values computed beside the pass (the space-syntax
// measures), carried by every writer like the pass's own columns.
struct NodeColumn {
  std::string name;                          // e.g. integration_hh:fog:advection
  const std::vector<double>* values = nullptr;  // one per node
};

// A visibility result with the names the user gave its conditions.
struct ScoreTable {
  const std::vector<Eigen::Vector3d>* eyes = nullptr;  // world frame
  const VisibilityResult* result = nullptr;
  std::vector<std::string> labels;                     // one per sigma, as the user wrote it
  std::vector<NodeColumn> extra;                       // after the pass's columns, in this order
};

// The space-syntax measures as node columns named MEASURE:LABEL (measure
// by measure, each condition in turn), pointing into `result`.
std::vector<NodeColumn> space_syntax_columns(const SpaceSyntaxResult& result, const std::vector<std::string>& labels);

// Column names in CSV order: x,y,z, then degree (when exact), for each label
// sum:L followed by avg:L (avg only when degree is exact),
// mean_distance,max_distance (when computed), sum_error_bound (when pruning),
// then the extra columns.
std::vector<std::string> score_columns(const ScoreTable& table);
// Values of one score column ("degree", "sum:L", "avg:L", "mean_distance",
// "max_distance", "sum_error_bound"); throws std::invalid_argument naming
// the available columns otherwise.
std::vector<double> score_values(const ScoreTable& table, const std::string& column);

// The score table as CSV x,y,z,degree,sum:COND,avg:COND,... (a file is staged).
void write_csv(const std::string& path, const ScoreTable& table);
void write_csv(std::ostream& out, const ScoreTable& table);

// ASCII PLY: x y z (double), red green blue (uchar, viridis colour map over
// the column's finite range; NaN grey) and the value itself (double).
void write_ply(const std::string& path, const ScoreTable& table, const std::string& column);
void write_ply(std::ostream& out, const ScoreTable& table, const std::string& column);

// Top-view heatmap drawn from an existing CSV by visgraph/scripts/vg_heatmap.py
// with Debian's python3 (matplotlib): one panel per column on one colour
// scale, covered cells (building footprints) in dark grey, nodes that see
// nothing as red crosses, axes in metres (with the CRS), a labelled colour bar.
struct HeatmapOptions {
  std::vector<std::string> columns;            // panels; see default_heatmap_columns
  std::string title;
  std::vector<Eigen::Vector2d> covered_cells;  // NodeSet::covered_cells, or empty
  std::string crs;                             // for the axis labels, or empty
};
void write_heatmap(const std::string& png_path, const std::string& csv_path, const HeatmapOptions& options);
// The same, drawn straight into `png_path` (a caller's staged temporary; a
// failure may leave it partial there).
void draw_heatmap(const std::string& png_path, const std::string& csv_path, const HeatmapOptions& options);
// One column: write_heatmap with a single panel and no footprints.
void write_heatmap(const std::string& png_path, const std::string& csv_path, const std::string& column,
                   const std::string& title);

// What a planner reads as "visible from here": the sum score S_S of every
// condition, one panel each (sum:LABEL ...), or the degree when there is no
// condition.  (The average S_A is highest in closed courtyards, where the few
// partners are near, and lowest in open streets: the opposite reading.)
std::vector<std::string> default_heatmap_columns(const ScoreTable& table);

// How each sigma was obtained, for the summary.
struct ConditionInfo {
  std::string label;
  double sigma = 0;        // 1/m
  double sigma_error = 0;  // 1/m (0 if not known)
  std::string model, convention, note;
};

// How a run was made, for the JSON summary.
struct RunInfo {
  std::string scene;              // file or generator spec
  std::string scene_report;       // describe(scene)
  std::string scene_format;       // "CityJSON 1.0", "OBJ", ... (empty for generated scenes)
  std::string crs;                // the scene's CRS, or empty
  std::string ground;             // where the nodes' ground came from, in words, or empty
  std::vector<std::string> warnings;  // what the run warned about
  std::string mode;               // "all-to-all" or "to-targets"
  std::size_t targets = 0;
  const NodeSet* grid = nullptr;  // null for given nodes
  double wavelength_m = 0;
  int threads = 0;
  double total_seconds = 0;
  std::vector<ConditionInfo> conditions;
  // The space-syntax measures, when computed: their graphs and options.
  const SpaceSyntaxResult* space_syntax = nullptr;
  double contrast_threshold = 0;
  int radius = 0;  // 0 = n
};

// JSON summary: nodes (and where the grid put them), pairs cast, visible
// fraction, min/max/mean per score, sigma with units and convention, pruning
// bound, time, pairs/s; with space syntax its threshold, radius, and per
// condition the lines kept and the components.  A few kB whatever the scene: lists of groups are
// cut to their first entries.
std::string summary_json(const ScoreTable& table, const RunInfo& info);

}  // namespace attenuvis::visgraph
