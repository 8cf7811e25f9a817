// `attenuvis vg`: weather-weighted visibility graph of a scene.  Parses the
// arguments, turns condition strings into sigma through the weather module
// and calls the visgraph library.
#include "commands.hpp"
#include "path_clashes.hpp"
#include "process_group.hpp"
#include "vg_city_options.hpp"
#include "vg_space_syntax.hpp"
#include "weather_options.hpp"

#include <attenuvis/io/number_text.hpp>
#include <attenuvis/io/staged_file.hpp>
#include <attenuvis/visgraph.hpp>
#include <attenuvis/visgraph/gis/city.hpp>
#include <attenuvis/visgraph/gis/geopackage.hpp>
#include <attenuvis/weather.hpp>

#include <chrono>
#include <fstream>
#include <filesystem>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
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
  bool spacing_given = false;  // --spacing on the command line (else: 1 m, coarsened to fit, see place_nodes)
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
  std::string out, ply, heatmap, summary, edges, color_by, geojson;
  bool quiet = false;
  bool allow_large = false;
  bool no_culling = false;
  std::string up_axis = "z", lod;
  CityArguments city;  // --terrain, footprints, --ground-plane, --gpkg (vg_city_options.hpp)
  SpaceSyntaxArguments space_syntax;  // --measures and its options (vg_space_syntax.hpp)
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// Every numeric option within its documented range (limits.hpp; --help and
// README say them), so that no value reaches the grid or Embree that would
// overflow, assert or make a meaningless grid.
void check_option_ranges(const VgArguments& a) {
  vg::check_range(a.spacing, vg::kMinSpacing, vg::kMaxSpacing, "--spacing", "m");
  vg::check_range(a.eye_height, 0.0, vg::kMaxEyeHeight, "--eye-height", "m");
  vg::check_range(a.max_slope, 0.0, 90.0, "--max-slope", "degrees");
  if (!(a.prune_below >= 0 && a.prune_below < 1))
    throw std::invalid_argument("--prune-below: " + io::significant(a.prune_below, 6) + " is outside [0, 1)");
  if (!(a.max_distance > 0))  // NaN fails too; inf (the default) means no limit
    throw std::invalid_argument("--max-distance: " + io::significant(a.max_distance, 6) + " is not a positive number of metres");
  vg::check_range(a.threads, 0, 1024, "--threads", "");
}

// Refuses a run whose pairs or memory exceed the default caps (or the
// machine's memory), saying what was asked and how to ask for less.
// --allow-large lifts the caps but not the machine's memory.
void check_work(const VgArguments& a, const vg::WorkEstimate& e) {
  const double memory = vg::physical_memory_bytes();
  const bool beyond_machine = memory > 0 && e.bytes > memory;
  if (a.allow_large && !beyond_machine) return;
  const bool too_many_pairs = e.pairs > vg::kDefaultMaxPairs;
  const bool too_much_memory = memory > 0 && e.bytes > 0.5 * memory;
  if (!too_many_pairs && !too_much_memory) return;
  std::string what = std::to_string(e.nodes) + " nodes" +
                     (e.targets ? " x " + std::to_string(e.targets) + " targets" : std::string()) + " = " +
                     io::significant(e.pairs, 3) + " pairs" +
                     (std::isfinite(e.radius) ? " within " + io::significant(e.radius, 4) + " m" : std::string()) +
                     ", " + io::significant(e.bytes / 1e9, 3) + " GB of accumulators on " + std::to_string(e.threads) +
                     " threads";
  throw std::invalid_argument(
      "the run is too large: " + what + " (limits: " + io::significant(vg::kDefaultMaxPairs, 3) +
      " pairs, half of the machine's " + io::significant(memory / 1e9, 3) +
      " GB). Reduce it with a larger --spacing, --max-distance, or --prune-below (with a positive sigma), "
      "fewer --threads for memory" +
      std::string(beyond_machine ? " (it needs more memory than the machine has)" : ", or pass --allow-large to run it anyway"));
}

// One ConditionInfo per comma-separated condition, in the user's spelling.
std::vector<vg::ConditionInfo> conditions_to_sigma(const VgArguments& a, double& wavelength_m) {
  std::vector<vg::ConditionInfo> out;
  const std::vector<std::string> labels = weather::split_condition_list(a.conditions);
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
    // Like every warning of vg, silent under --quiet and on all but the
    // first process under mpirun; the note carries it into the outputs.
    if (!s.shortfall.empty() && !a.quiet) std::cerr << "warning: " << label << ": " << s.shortfall << "\n";
    info.sigma = s.per_m;
    info.sigma_error = s.error_per_m;
    info.model = s.model;
    info.convention = s.convention;
    info.note = s.note;
    out.push_back(info);
  }
  return out;
}

struct SceneInput {
  vg::Mesh mesh;
  std::string format;
  std::vector<std::string> warnings;
  std::optional<vg::HeightGrid> terrain;  // the DEM window (--terrain)
  std::string terrain_source;
  std::string ground;                     // where the nodes' ground came from, in words
};

void warn(SceneInput& input, const std::string& text, bool quiet) {
  input.warnings.push_back(text);
  if (!quiet) std::cerr << "warning: " << text << "\n";
}

SceneInput read_scene(const VgArguments& a) {
  SceneInput input;
  if (vg::is_scene_spec(a.scene)) {
    if (wants_city_input(a.city))
      throw std::invalid_argument("--terrain, --height-field and --levels-field apply to scene files, not to '" +
                                  a.scene + "'");
    input.mesh = vg::scene_from_spec(a.scene);
    return input;
  }
  vg::SceneFileOptions options;
  options.obj_up_axis = vg::parse_up_axis(a.up_axis);
  options.lod = a.lod;
  vg::gis::CityModel city = vg::gis::load_city(a.scene, city_options(a.city, options, !a.nodes_file.empty()));
  input.mesh = std::move(city.mesh);
  input.format = city.format;
  input.terrain = std::move(city.terrain);
  input.terrain_source = city.terrain_source;
  input.ground = city.ground;
  for (const std::string& w : city.warnings) warn(input, w, a.quiet);
  return input;
}

std::vector<Eigen::Vector3d> read_node_file(const std::string& path, SceneInput& input, bool quiet) {
  std::string crs;
  std::vector<Eigen::Vector3d> points = vg::read_nodes(path, &crs);
  if (!crs.empty() && !input.mesh.crs.empty() && vg::short_crs_name(crs) != vg::short_crs_name(input.mesh.crs))
    warn(input, path + " is in " + crs + " but the scene in " + input.mesh.crs + ": the points are used as they are",
         quiet);
  return points;
}

// The next spacing of the "nice" sequence 1, 1.5, 2, 3, 4, 5, 6, 8 x 10^k m after h.
double next_spacing(double h) {
  const double decade = std::pow(10.0, std::floor(std::log10(h) + 1e-9));
  for (double f : {1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (f * decade > h * (1 + 1e-9)) return f * decade;
  return 10 * decade;
}

// Without --spacing, an all-to-all grid starts at 1 m and is coarsened along
// next_spacing() until its cells and pairs fit the default limits
// (kDefaultMaxGridCells, kDefaultMaxPairs): a real district at 1 m has
// 10^5-10^6 nodes and 10^10-10^12 pairs, hours to days of work.  The choice is
// announced and recorded in the summary; --spacing (with --allow-large)
// asks for any grid explicitly.
struct SpacingChoice {
  bool automatic = false;
  double pairs_limit = vg::kDefaultMaxPairs;
};

double unordered_pairs(std::size_t n) { return 0.5 * static_cast<double>(n) * (static_cast<double>(n) - 1); }

// The node grid on the ground --ground-plane asks for: a plane first (yes,
// Z), or, when the grid finds no ground, the one add_ground chooses (auto);
// `no_ground`: the model had none of its own.
vg::NodeSet grid_on_ground(const VgArguments& a, SceneInput& input, std::unique_ptr<vg::Scene>& scene,
                           vg::NodeGridOptions& options, bool& no_ground) {
  const GroundPlaneChoice ground = ground_plane_choice(a.city, a.eye_height);
  const auto add_ground = [&] {
    const vg::GroundMade made = make_ground(input.mesh, ground.request);
    input.ground = made.description;
    if (made.floating > 0)
      warn(input, std::to_string(made.floating) + " buildings stand more than the eye height above the ground plane " +
                      "at z = " + io::shortest(made.plane_z) + " m: eye points there are below their bases", a.quiet);
    scene = std::make_unique<vg::Scene>(input.mesh);
    if (!options.walkable.empty())
      options.walkable.push_back(made.inferred ? vg::kInferredGroundGroup : vg::kGroundPlaneGroup);
    return made;
  };
  if (ground.now) add_ground();
  vg::NodeSet grid = vg::generate_nodes(*scene, options);
  no_ground = !vg::found_ground(*scene, grid);
  if (no_ground && ground.automatic) {
    const vg::GroundMade made = add_ground();
    warn(input, "the scene has no ground (buildings only?): nodes stand on " + made.description +
                    (made.inferred ? " (--terrain DEM gives the surveyed ground)"
                                   : " (--ground-plane Z or --terrain DEM give another ground, --ground-plane no refuses)"),
         a.quiet);
    grid = vg::generate_nodes(*scene, options);
  }
  return grid;
}

// The node grid; on the ground of grid_on_ground.
vg::NodeSet place_nodes(const VgArguments& a, SceneInput& input, std::unique_ptr<vg::Scene>& scene,
                        const SpacingChoice& choice) {
  vg::NodeGridOptions options;
  options.spacing = a.spacing;
  options.eye_height = a.eye_height;
  options.max_slope_deg = a.max_slope;
  options.walkable = a.walkable.empty() ? vg::default_walkable_groups(a.scene) : split(a.walkable, ',');
  options.max_cells = a.allow_large ? 0.0 : vg::kDefaultMaxGridCells;
  if (choice.automatic)
    while (options.spacing < vg::kMaxSpacing && vg::estimate_grid(*scene, options.spacing).cells > vg::kDefaultMaxGridCells)
      options.spacing = next_spacing(options.spacing);
  const vg::GridEstimate cells = vg::estimate_grid(*scene, options.spacing);
  if (!a.allow_large && cells.cells > vg::kDefaultMaxGridCells)
    throw std::invalid_argument("--spacing " + io::shortest(options.spacing) + " m over this scene gives " +
                                io::significant(cells.nx, 3) + " x " + io::significant(cells.ny, 3) + " = " +
                                io::significant(cells.cells, 3) + " grid cells (" +
                                io::significant(cells.bytes / 1e9, 3) + " GB while placing), more than the " +
                                io::significant(vg::kDefaultMaxGridCells, 3) +
                                " allowed: use a larger --spacing, or --allow-large to run it anyway");
  bool no_ground = false;
  vg::NodeSet grid = grid_on_ground(a, input, scene, options, no_ground);
  if (input.ground.empty()) input.ground = no_ground ? "none" : "the model's own surfaces";
  if (choice.automatic) {
    const std::size_t first_nodes = grid.eyes.size();
    const double first_spacing = options.spacing;
    while (unordered_pairs(grid.eyes.size()) > choice.pairs_limit && options.spacing < vg::kMaxSpacing) {
      options.spacing = next_spacing(options.spacing);
      grid = vg::generate_nodes(*scene, options);
    }
    if (options.spacing != a.spacing) {
      grid.spacing_rule = "no --spacing: " + io::shortest(options.spacing) + " m, the finest of 1, 1.5, 2, 3, 4, 5, 6, 8 x 10^k m within the default limits (" +
                          io::significant(vg::kDefaultMaxGridCells, 3) + " grid cells, " +
                          io::significant(choice.pairs_limit, 3) + " pairs); at " + io::shortest(first_spacing) +
                          " m the grid had " + std::to_string(first_nodes) + " nodes = " +
                          io::significant(unordered_pairs(first_nodes), 3) + " pairs";
      if (!a.quiet)
        std::cerr << "spacing: " << grid.spacing_rule << " (give --spacing, and --allow-large, for a finer grid)\n";
    }
  }
  if (!a.quiet) {
    std::vector<std::string> where;
    for (const vg::SurfaceCount& s : grid.by_surface) where.push_back(s.name + " " + std::to_string(s.nodes));
    std::cerr << "nodes: " << grid.eyes.size() << " of " << grid.cells << " grid cells (dropped: " << grid.covered
              << " covered, " << grid.too_steep << " too steep, " << grid.no_headroom << " without headroom, "
              << grid.no_surface << " over no surface)\n  placed by: " << grid.rule << "\n  on: "
              << vg::preview_names(where, 8, "(--summary lists the 20 largest)") << "\n  ground: " << input.ground
              << "\n";
  }
  if (grid.elevated > 0)
    warn(input, std::to_string(grid.elevated) + " nodes stand more than " + io::shortest(options.elevated_height) +
                    " m above the lowest surface under them (up to " + io::significant(grid.max_elevation, 3) +
                    " m): roofs or decks? --walkable chooses the surfaces", a.quiet);
  if (grid.eyes.empty())
    throw std::runtime_error(no_ground && a.city.ground_plane == "no"
                                 ? "no ground under the node grid (buildings only?): --ground-plane yes stands nodes "
                                   "on a plane at the scene's lowest z"
                                 : "no walkable surface under the node grid: no nodes (--walkable chooses surfaces)");
  return grid;
}

// Refuses, before any work, options that contradict each other or lie
// outside their ranges, outputs that would overwrite an input or each other,
// and existing outputs that are not regular files (a device, a directory).
void check_arguments(const VgArguments& a) {
  if (!a.targets_file.empty() && !a.target_point.empty())
    throw std::invalid_argument("give --targets or --target-point, not both");
  if (!a.edges.empty() && process_count() > 1)
    throw std::invalid_argument("--edges is written by a single process: run it without mpirun (the scores "
                                "are the same; the edge list's order is that of one process)");
  refuse_path_clashes({{"--out", a.out}, {"--ply", a.ply}, {"--heatmap", a.heatmap}, {"--summary", a.summary},
                       {"--edges", a.edges}, {"--geojson", a.geojson}, {"--gpkg", a.city.gpkg}},
                      {{"the scene", vg::is_scene_spec(a.scene) ? "" : a.scene},
                       {"--nodes", a.nodes_file},
                       {"--targets", a.targets_file},
                       {"--terrain", a.city.terrain}});
  check_option_ranges(a);
  ground_plane_choice(a.city, a.eye_height);  // refuses a bad --ground-plane before anything is read
  check_space_syntax_arguments(a.space_syntax, !a.targets_file.empty() || !a.target_point.empty(),
                               a.prune_below > 0 || a.deprecated_tolerance > 0);
  for (const std::string* path : {&a.out, &a.ply, &a.heatmap, &a.summary, &a.edges, &a.geojson, &a.city.gpkg})
    if (!path->empty()) io::require_regular_or_absent(*path);
}

// What a run's outputs are made of, gathered step by step by run_vg.
struct VgRun {
  std::chrono::steady_clock::time_point start;
  std::vector<vg::ConditionInfo> conditions;
  double wavelength_m = 0;
  SceneInput input;
  std::unique_ptr<vg::Scene> scene;
  std::unique_ptr<vg::NodeSet> grid;  // null for nodes given in a file
  std::vector<Eigen::Vector3d> eyes, targets;
  vg::VisibilityResult result;
  std::unique_ptr<vg::GraphCollector> graph;  // with --measures: the lines of sight, kept for the measures
  vg::SpaceSyntaxResult measures;
};

// Eyes from --nodes or the node grid (which may give the scene a ground
// plane), and targets from --targets or --target-point.
void read_or_place_nodes(const VgArguments& a, VgRun& run) {
  if (!a.nodes_file.empty()) {
    run.eyes = read_node_file(a.nodes_file, run.input, a.quiet);
    if (run.input.terrain) vg::check_nodes_on_terrain(*run.input.terrain, run.eyes, run.input.terrain_source);
  } else {
    // The spacing is chosen only for an unbounded all-to-all run; with a
    // radius (--max-distance, --prune-below) or targets the pair count is not
    // N^2/2 and the user's 1 m stands, checked by check_work.
    SpacingChoice choice;
    choice.automatic = !a.spacing_given && !a.allow_large && a.targets_file.empty() && a.target_point.empty() &&
                       std::isinf(a.max_distance) && a.prune_below == 0;
    run.grid = std::make_unique<vg::NodeSet>(place_nodes(a, run.input, run.scene, choice));
    run.eyes = run.grid->eyes;
  }
  if (!a.targets_file.empty()) run.targets = read_node_file(a.targets_file, run.input, a.quiet);
  if (!a.target_point.empty()) run.targets.push_back(vg::parse_point(a.target_point));
}

vg::VisibilityOptions pass_options(const VgArguments& a, const std::vector<vg::ConditionInfo>& conditions) {
  vg::VisibilityOptions options;
  for (const vg::ConditionInfo& c : conditions) options.sigmas.push_back(c.sigma);
  options.distance_stats = a.distances;
  options.prune_below = a.prune_below;
  options.max_distance = a.max_distance;
  options.threads = a.threads;
  options.progress = !a.quiet;
  options.culling = !a.no_culling;
  options.share = process_share();
  return options;
}

// With --measures the pass's lines of sight go into a graph (its memory
// checked first), beside any other edge sink.
void keep_lines_of_sight(const VgArguments& a, VgRun& run, const vg::WorkEstimate& work,
                         vg::VisibilityOptions& options) {
  vg::SpaceSyntaxOptions probe;
  probe.sigmas = options.sigmas;
  probe.measures = vg::parse_measures(a.space_syntax.measures);
  probe.contrast_threshold = a.space_syntax.contrast_threshold;
  probe.storage = graph_storage(a.space_syntax.graph);
  probe.threads = a.threads;
  const vg::SpaceSyntaxEstimate estimate = vg::estimate_space_syntax(run.eyes.size(), work.pairs, probe);
  check_space_syntax_memory(estimate, run.eyes.size(), a.allow_large);
  if (!a.quiet)
    std::cerr << "space syntax: the lines of sight as " << (estimate.bit_rows ? "bit rows" : "CSR lists") << ", "
              << io::significant(estimate.peak_bytes / 1e6, 3) << " MB at most\n";
  run.graph = std::make_unique<vg::GraphCollector>(run.eyes, estimate.bit_rows);
  options.edge_sink = run.graph->sink();
}

// The measures on the pass's graph, every process its share.
void measure_space_syntax(const VgArguments& a, VgRun& run) {
  std::vector<double> sigmas;
  for (const vg::ConditionInfo& c : run.conditions) sigmas.push_back(c.sigma);
  const double spacing = run.grid ? run.grid->spacing : a.spacing_given ? a.spacing : 0.0;
  const vg::SpaceSyntaxOptions options = space_syntax_options(a.space_syntax, sigmas, run.eyes, spacing, a.threads);
  run.measures = vg::space_syntax(run.graph->finish(options.share), options);
  run.graph.reset();
  if (!a.quiet)
    std::cerr << "space syntax: " << run.measures.columns.size() << " columns in " << run.measures.seconds << " s\n";
}

// The visibility pass, once its work is known to fit (check_work).  With
// --edges the edge list streams into its staged temporary (never held
// whole).
void run_pass(const VgArguments& a, VgRun& run, io::StagedFiles& staged) {
  vg::VisibilityOptions options = pass_options(a, run.conditions);
  const vg::WorkEstimate work = vg::estimate_work(run.eyes, run.targets.empty() ? nullptr : &run.targets, options);
  check_work(a, work);
  if (!a.quiet)
    std::cerr << "work: " << io::significant(work.pairs, 3) << " pairs to consider, "
              << io::significant(work.bytes / 1e6, 3) << " MB of accumulators\n";
  if (a.space_syntax.wanted()) keep_lines_of_sight(a, run, work, options);
  auto pass = [&] {
    run.result = run.targets.empty() ? vg::all_to_all(*run.scene, run.eyes, options)
                                     : vg::to_targets(*run.scene, run.eyes, run.targets, options);
  };
  if (a.edges.empty()) {
    pass();
    return;
  }
  const std::string edges_temporary = staged.add(a.edges).temporary_path();
  std::ofstream out(edges_temporary, std::ios::binary | std::ios::trunc);
  out << (run.targets.empty() ? "i,j,distance\n" : "node,target,distance\n");
  out.precision(std::numeric_limits<double>::max_digits10);
  options.edge_sink = [&out, graph = options.edge_sink](const std::vector<vg::Edge>& edges) {
    if (graph) graph(edges);
    for (const vg::Edge& e : edges) out << e.i << "," << e.j << "," << e.distance << "\n";
  };
  pass();
  out.close();
  if (!out) throw std::runtime_error("error while writing '" + a.edges + "' (disk full?)");
}

int run_radius(const VgArguments& a) { return a.space_syntax.radius == "n" ? 0 : std::stoi(a.space_syntax.radius); }

vg::RunInfo run_info(const VgArguments& a, const VgRun& run) {
  vg::RunInfo info;
  info.scene = a.scene;
  info.scene_report = vg::describe(*run.scene);
  info.scene_format = run.input.format;
  info.crs = run.input.mesh.crs;
  info.ground = run.input.ground;
  info.warnings = run.input.warnings;
  info.mode = run.targets.empty() ? "all-to-all" : "to-targets";
  info.targets = run.targets.size();
  info.grid = run.grid.get();
  info.wavelength_m = run.wavelength_m;
  info.threads = a.threads;
  info.conditions = run.conditions;
  if (a.space_syntax.wanted()) {
    info.space_syntax = &run.measures;
    info.contrast_threshold = a.space_syntax.contrast_threshold;
    info.radius = run_radius(a);
  }
  info.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - run.start).count();
  return info;
}

// Stages every output beside its destination (the edge list is already
// there); the caller renames them all into place.  `panels`: the columns
// the PLY (the first) and the heatmap show.
void stage_outputs(const VgArguments& a, const VgRun& run, const vg::ScoreTable& table,
                   const std::vector<std::string>& panels, io::StagedFiles& staged) {
  const auto stage_text = [&staged](const std::string& path, const std::string& text) {
    io::StagedFile& file = staged.add(path);
    file.write(text);
    return file.temporary_path();
  };
  std::ostringstream csv;
  vg::write_csv(csv, table);
  const std::string csv_temporary = stage_text(a.out, csv.str());
  if (!a.geojson.empty()) stage_text(a.geojson, vg::geojson_text(table, run.input.mesh.crs));
  if (!a.city.gpkg.empty()) stage_text(a.city.gpkg, vg::gis::geopackage_bytes(table, run.input.mesh.crs));
  if (!a.ply.empty()) {
    std::ostringstream ply;
    vg::write_ply(ply, table, panels.front());
    stage_text(a.ply, ply.str());
  }
  if (!a.heatmap.empty()) {
    vg::HeatmapOptions heatmap;
    heatmap.columns = panels;
    heatmap.title = std::filesystem::path(a.scene).filename().string();
    if (run.grid) heatmap.covered_cells = run.grid->covered_cells;
    heatmap.crs = vg::short_crs_name(run.input.mesh.crs);
    vg::draw_heatmap(staged.add(a.heatmap).temporary_path(), csv_temporary, heatmap);
  }
  if (!a.summary.empty()) stage_text(a.summary, vg::summary_json(table, run_info(a, run)));
}

void report_pass(const vg::VisibilityResult& result) {
  if (!result.pruning_note.empty()) std::cerr << "pruning: " << result.pruning_note << "\n";
  std::cerr << "visibility: " << result.nodes << " nodes, " << result.pairs_total << " pairs ("
            << result.pairs_cast << " cast, " << result.pairs_culled_visible << " culled in sight, "
            << result.pairs_culled_blocked << " culled blocked, " << result.pairs_visible << " visible) in "
            << result.seconds << " s (clustering and classifying " << result.culling_seconds << " s, "
            << result.culling_bytes / 1e6 << " MB of cluster records)"
            << (process_count() > 1 ? " on " + std::to_string(process_count()) + " processes" : std::string())
            << " = " << (result.seconds > 0 ? result.pairs_total / result.seconds / 1e6 : 0.0) << " M pairs/s\n";
}

// Under mpirun every process reads the same input and runs the same checks
// (so bad input fails identically everywhere); each accumulates its share of
// the pass, the shares are summed exactly, and only the first process
// reports and writes the outputs.  Every output is staged and renamed into
// place only when all of them were written.
void run_vg(const VgArguments& given) {
  VgRun run;
  run.start = std::chrono::steady_clock::now();
  VgArguments a = given;
  const bool root = is_root_process();
  if (!root) a.quiet = true;
  check_arguments(a);
  run.conditions = conditions_to_sigma(a, run.wavelength_m);

  run.input = read_scene(a);
  if (!a.city.gpkg.empty()) vg::gis::check_geopackage_crs(run.input.mesh.crs);
  run.scene = std::make_unique<vg::Scene>(run.input.mesh);
  if (!a.quiet) std::cerr << "scene " << a.scene << ": " << vg::describe(*run.scene) << "\n";
  read_or_place_nodes(a, run);

  io::StagedFiles staged;
  run_pass(a, run, staged);
  if (a.space_syntax.wanted()) measure_space_syntax(a, run);

  vg::ScoreTable table;
  table.eyes = &run.eyes;
  table.result = &run.result;
  for (const vg::ConditionInfo& c : run.conditions) table.labels.push_back(c.label);
  table.extra = vg::space_syntax_columns(run.measures, table.labels);
  // The sum score by default: the average is highest in closed courtyards
  // and lowest in open streets, the opposite of a visibility map's reading.
  const std::vector<std::string> panels =
      a.color_by.empty() ? vg::default_heatmap_columns(table) : std::vector<std::string>{a.color_by};
  if (!a.ply.empty() || !a.heatmap.empty()) vg::score_values(table, panels.front());  // check the name before writing
  synchronize_processes();  // every check passed everywhere: nothing can end the writer midway
  if (!root) return;        // every process holds the totals; the first one writes them
  stage_outputs(a, run, table, panels, staged);
  staged.commit_all();
  if (!a.quiet) report_pass(run.result);
}
}  // namespace

void register_visgraph(CLI::App& app) {
  auto args = std::make_shared<VgArguments>();
  CLI::App* vgc = app.add_subcommand("vg", "visibility graph of a scene, weighted by the contrast C = exp(-sigma d) in each "
                                           "condition");
  vgc->add_option("scene", args->scene,
                  "scene file (CityJSON .json/.city.json/.jsonl, glTF .gltf/.glb, OBJ; recognised by content; "
                  "or footprints with --height-field; "
                  "a regular file <= 2 GiB, |coordinates| <= 1e7 m, faces <= 10000 vertices), "
                  "or layout:0..4, city, city:SEED")
      ->required();
  vgc->add_option("--up-axis", args->up_axis, "up axis of an OBJ file: z or y")->capture_default_str();
  vgc->add_option("--lod", args->lod, "CityJSON level of detail to read, e.g. 2.2 (default: each object's highest)");
  add_city_options(vgc, args->city);
  auto* spacing = vgc->add_option("--spacing", args->spacing,
                  "node grid spacing, 0.001 to 10000 m (default 1 m, coarsened to 1.5, 2, 3, 4, 5, 6, 8 x 10^k m "
                  "when an all-to-all grid would exceed the default limits; the choice is printed)")
      ->capture_default_str();
  vgc->add_option("--eye-height", args->eye_height, "eye height above the walkable surface, 0 to 1000 m")
      ->capture_default_str();
  vgc->add_option("--walkable", args->walkable,
                  "walkable groups or classes (CityJSON semantics/types), comma-separated; * = every surface "
                  "(default: the data decide, never roofs; floor for layouts; sidewalk,crosswalk for city)");
  vgc->add_option("--max-slope", args->max_slope, "steepest walkable surface, 0 to 90 degrees")->capture_default_str();
  vgc->add_option("--nodes", args->nodes_file, "eye positions instead of the grid: CSV x,y,z or GeoJSON points (|x|, |y|, |z| <= 1e7 m, file <= 512 MiB)");
  vgc->add_option("--targets", args->targets_file,
                  "targets (CSV x,y,z or GeoJSON points): nodes -> targets instead of all pairs");
  vgc->add_option("--target-point", args->target_point, "one target x,y,z");
  vgc->add_option("--conditions", args->conditions,
                  "comma-separated conditions, e.g. clear,rain:8,fog:advection,snow:dry:4,sigma:0.01")
      ->required();
  // --tolerance is the Mie tolerance in sigma and table; here it was the
  // pruning threshold, now --prune-below, and stays as a deprecated alias.
  add_weather_options(vgc, args->weather, {/*wavelength=*/true, /*tolerance=*/false});
  auto* prune = vgc->add_option("--prune-below", args->prune_below,
                                "prune pairs whose C < eps for every condition (certified bound), eps in [0, 1)");
  auto* old_prune = vgc->add_option("--tolerance", args->deprecated_tolerance,
                                    "deprecated: the old name of --prune-below");
  old_prune->excludes(prune);
  vgc->add_option("--max-distance", args->max_distance, "pairs farther than this (m, > 0) are not lines of sight");
  vgc->add_option("--threads", args->threads, "worker threads, 0 to 1024 (0 = all cores)")->capture_default_str();
  vgc->add_flag("--distances", args->distances, "add mean_distance and max_distance columns");
  vgc->add_option("--out", args->out, "CSV of per-node scores")->required();
  vgc->add_option("--ply", args->ply, "PLY point cloud coloured by --color-by");
  vgc->add_option("--geojson", args->geojson, "GeoJSON point layer of the nodes, every score a property, in the scene's CRS");
  vgc->add_option("--heatmap", args->heatmap,
                  "PNG top-view heatmap (default: sum score, one panel per condition on one scale)");
  vgc->add_option("--color-by", args->color_by, "one score column for --ply/--heatmap (default sum:FIRST)");
  vgc->add_option("--summary", args->summary, "JSON summary");
  vgc->add_option("--edges", args->edges, "CSV edge list i,j,distance (O(edges) output)");
  add_space_syntax_options(vgc, args->space_syntax);
  vgc->add_flag("--quiet", args->quiet, "no report or progress on stderr");
  vgc->add_flag("--no-culling", args->no_culling,
                "cast every pair (same results; the reference the exact culling is tested against)");
  vgc->add_flag("--allow-large", args->allow_large,
                "run even above the default caps: 1e7 grid cells, 2e9 pairs, half the machine's memory "
                "(never above all of it)");
  vgc->callback([args, old_prune, spacing] {
    args->spacing_given = spacing->count() > 0;
    args->city.allow_large = args->allow_large;
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
