// `attenuvis vg`: weather-weighted visibility graph of a scene.  Parses the
// arguments, turns condition strings into sigma through the weather module
// and calls the visgraph library.
#include "commands.hpp"
#include "path_clashes.hpp"
#include "weather_options.hpp"

#include <attenuvis/visgraph.hpp>
#include <attenuvis/weather.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace attenuvis::cli {
namespace {
namespace vg = attenuvis::visgraph;

struct VgArguments {
  std::string scene;
  double spacing = 1.0;
  double eye_height = 1.7;
  std::string walkable;
  double max_slope = 90.0;
  std::string nodes_file, targets_file, target_point;
  std::string conditions;
  WeatherOptions weather;
  double prune_below = 0;
  double deprecated_tolerance = 0;  // --tolerance, the old name of --prune-below
  double max_distance = std::numeric_limits<double>::infinity();
  int threads = 0;
  bool distances = false;
  std::string out, ply, heatmap, summary, edges, color_by;
  bool quiet = false;
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// One ConditionInfo per comma-separated condition, in the user's spelling.
std::vector<vg::ConditionInfo> conditions_to_sigma(const VgArguments& a, double& wavelength_m) {
  std::vector<vg::ConditionInfo> out;
  const std::vector<std::string> labels = split(a.conditions, ',');
  if (labels.empty()) throw std::invalid_argument("--conditions: give at least one condition");
  const weather::Settings settings = weather_settings(a.weather);
  wavelength_m = cli::wavelength_m(a.weather);
  for (const std::string& label : labels) {
    if (label.empty()) throw std::invalid_argument("--conditions: empty condition in '" + a.conditions + "'");
    for (const vg::ConditionInfo& seen : out)
      if (seen.label == label) throw std::invalid_argument("--conditions: '" + label + "' given twice");
    vg::ConditionInfo info;
    info.label = label;
    const weather::Sigma s = weather::sigma(weather::parse_condition(label), wavelength_m, settings);
    info.sigma = s.per_m;
    info.sigma_error = s.error_per_m;
    info.model = s.model;
    info.convention = s.convention;
    info.note = s.note;
    out.push_back(info);
  }
  return out;
}

std::vector<std::string> default_walkable(const std::string& scene) {
  if (scene.rfind("layout:", 0) == 0) return {"floor"};
  if (scene == "city" || scene.rfind("city:", 0) == 0) return {"sidewalk", "crosswalk"};
  return {};
}

void run_vg(const VgArguments& a) {
  const auto start = std::chrono::steady_clock::now();
  if (!a.targets_file.empty() && !a.target_point.empty())
    throw std::invalid_argument("give --targets or --target-point, not both");
  refuse_path_clashes({{"--out", a.out}, {"--ply", a.ply}, {"--heatmap", a.heatmap}, {"--summary", a.summary},
                       {"--edges", a.edges}},
                      {{"the scene", vg::is_scene_spec(a.scene) ? "" : a.scene},
                       {"--nodes", a.nodes_file},
                       {"--targets", a.targets_file}});
  double wavelength_m = 0;
  const std::vector<vg::ConditionInfo> conditions = conditions_to_sigma(a, wavelength_m);

  const vg::Mesh mesh = vg::is_scene_spec(a.scene) ? vg::scene_from_spec(a.scene) : vg::load_obj(a.scene);
  const vg::Scene scene(mesh);
  if (!a.quiet) std::cerr << "scene " << a.scene << ": " << vg::describe(scene) << "\n";

  std::unique_ptr<vg::NodeSet> grid;
  std::vector<Eigen::Vector3d> eyes;
  if (!a.nodes_file.empty()) {
    eyes = vg::read_nodes_csv(a.nodes_file);
  } else {
    vg::NodeGridOptions options;
    options.spacing = a.spacing;
    options.eye_height = a.eye_height;
    options.max_slope_deg = a.max_slope;
    options.walkable = a.walkable.empty() ? default_walkable(a.scene) : split(a.walkable, ',');
    grid = std::make_unique<vg::NodeSet>(vg::generate_nodes(scene, options));
    eyes = grid->eyes;
    if (!a.quiet)
      std::cerr << "nodes: " << eyes.size() << " of " << grid->cells << " grid cells (dropped: " << grid->covered
                << " covered, " << grid->too_steep << " too steep, " << grid->no_headroom << " without headroom, "
                << grid->no_surface << " over no surface)\n";
    if (eyes.empty()) throw std::runtime_error("no walkable surface under the node grid: no nodes");
  }
  std::vector<Eigen::Vector3d> targets;
  if (!a.targets_file.empty()) targets = vg::read_nodes_csv(a.targets_file);
  if (!a.target_point.empty()) targets.push_back(vg::parse_point(a.target_point));

  vg::VisibilityOptions options;
  for (const vg::ConditionInfo& c : conditions) options.sigmas.push_back(c.sigma);
  options.distance_stats = a.distances;
  options.tolerance = a.prune_below;
  options.max_distance = a.max_distance;
  options.threads = a.threads;
  options.progress = !a.quiet;

  vg::VisibilityResult result;
  auto run = [&] {
    result = targets.empty() ? vg::all_to_all(scene, eyes, options) : vg::to_targets(scene, eyes, targets, options);
  };
  if (a.edges.empty()) {
    run();
  } else {
    vg::write_atomically(a.edges, [&](std::ostream& out) {
      out << (targets.empty() ? "i,j,distance\n" : "node,target,distance\n");
      out.precision(std::numeric_limits<double>::max_digits10);
      options.edge_sink = [&out](const std::vector<vg::Edge>& edges) {
        for (const vg::Edge& e : edges) out << e.i << "," << e.j << "," << e.distance << "\n";
      };
      run();
    });
  }

  vg::ScoreTable table;
  table.eyes = &eyes;
  table.result = &result;
  for (const vg::ConditionInfo& c : conditions) table.labels.push_back(c.label);
  const std::string color_by =
      !a.color_by.empty() ? a.color_by : result.degree_exact ? "avg:" + table.labels[0] : "sum:" + table.labels[0];
  if (!a.ply.empty() || !a.heatmap.empty()) vg::score_values(table, color_by);  // check the name before writing
  vg::write_csv(a.out, table);
  if (!a.ply.empty()) vg::write_ply(a.ply, table, color_by);
  if (!a.heatmap.empty()) vg::write_heatmap(a.heatmap, a.out, color_by, a.scene + ": " + color_by);
  if (!a.summary.empty()) {
    vg::RunInfo info;
    info.scene = a.scene;
    info.scene_report = vg::describe(scene);
    info.mode = targets.empty() ? "all-to-all" : "to-targets";
    info.targets = targets.size();
    info.grid = grid.get();
    info.wavelength_m = wavelength_m;
    info.threads = a.threads;
    info.conditions = conditions;
    info.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string json = vg::summary_json(table, info);
    vg::write_atomically(a.summary, [&](std::ostream& out) { out << json; });
  }
  if (!a.quiet)
    std::cerr << "visibility: " << result.nodes << " nodes, " << result.pairs_total << " pairs ("
              << result.pairs_cast << " cast, " << result.pairs_visible << " visible) in " << result.seconds
              << " s = " << (result.seconds > 0 ? result.pairs_total / result.seconds / 1e6 : 0.0)
              << " M pairs/s\n";
}
}  // namespace

void register_visgraph(CLI::App& app) {
  auto args = std::make_shared<VgArguments>();
  CLI::App* vgc = app.add_subcommand("vg", "Visibility graph weighted by contrast ratio C = exp(-sigma d)");
  vgc->add_option("scene", args->scene, "OBJ file, or layout:0..4, city, city:SEED")->required();
  vgc->add_option("--spacing", args->spacing, "node grid spacing (m)")->capture_default_str();
  vgc->add_option("--eye-height", args->eye_height, "eye height above the walkable surface (m)")->capture_default_str();
  vgc->add_option("--walkable", args->walkable,
                  "walkable OBJ groups, comma-separated (default: all; floor for layouts; sidewalk,crosswalk for city)");
  vgc->add_option("--max-slope", args->max_slope, "steepest walkable surface (degrees)")->capture_default_str();
  vgc->add_option("--nodes", args->nodes_file, "CSV x,y,z of eye positions instead of the grid");
  vgc->add_option("--targets", args->targets_file, "CSV x,y,z of targets: nodes -> targets instead of all pairs");
  vgc->add_option("--target-point", args->target_point, "one target x,y,z");
  vgc->add_option("--conditions", args->conditions,
                  "comma-separated conditions, e.g. clear,rain:8,fog:advection,snow:dry:4,sigma:0.01")
      ->required();
  // --tolerance is the Mie tolerance in sigma and table; here it was the
  // pruning threshold, now --prune-below, and stays as a deprecated alias.
  add_weather_options(vgc, args->weather, {/*wavelength=*/true, /*tolerance=*/false});
  auto* prune = vgc->add_option("--prune-below", args->prune_below,
                                "prune pairs whose C < eps for every condition (certified bound)");
  auto* old_prune = vgc->add_option("--tolerance", args->deprecated_tolerance,
                                    "deprecated: the old name of --prune-below");
  old_prune->excludes(prune);
  vgc->add_option("--max-distance", args->max_distance, "pairs farther than this (m) are not lines of sight");
  vgc->add_option("--threads", args->threads, "worker threads (0 = all cores)")->capture_default_str();
  vgc->add_flag("--distances", args->distances, "add mean_distance and max_distance columns");
  vgc->add_option("--out", args->out, "CSV of per-node scores")->required();
  vgc->add_option("--ply", args->ply, "PLY point cloud coloured by --color-by");
  vgc->add_option("--heatmap", args->heatmap, "PNG top-view heatmap of --color-by");
  vgc->add_option("--color-by", args->color_by, "score column for --ply/--heatmap (default avg:FIRST)");
  vgc->add_option("--summary", args->summary, "JSON summary");
  vgc->add_option("--edges", args->edges, "CSV edge list i,j,distance (O(edges) output)");
  vgc->add_flag("--quiet", args->quiet, "no report or progress on stderr");
  vgc->callback([args, old_prune] {
    if (old_prune->count() > 0) {
      if (!args->quiet)
        std::cerr << "attenuvis vg: --tolerance is deprecated here (it means the Mie tolerance in sigma and table); "
                     "use --prune-below\n";
      args->prune_below = args->deprecated_tolerance;
    }
    run_vg(*args);
  });
}

}  // namespace attenuvis::cli
