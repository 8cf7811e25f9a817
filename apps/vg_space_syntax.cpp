// The space-syntax options of `attenuvis vg` (vg_space_syntax.hpp).
#include "vg_space_syntax.hpp"

#include "process_group.hpp"

#include <attenuvis/io/number_text.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>

#include <limits>
#include <sstream>
#include <stdexcept>

namespace attenuvis::cli {

namespace vg = attenuvis::visgraph;

namespace {
int parse_radius(const std::string& text) {
  if (text == "n") return 0;
  std::size_t used = 0;
  int steps = 0;
  try {
    steps = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || steps < 1 || steps > 1000000)
    throw std::invalid_argument("--radius: expected n or a number of steps from 1 to 1000000, got '" + text + "'");
  return steps;
}

// The node nearest each point of "x,y,z;x,y,z".
std::vector<std::uint32_t> origins(const std::string& text, const std::vector<Eigen::Vector3d>& eyes) {
  std::vector<std::uint32_t> out;
  std::stringstream in(text);
  std::string point;
  while (std::getline(in, point, ';')) {
    const Eigen::Vector3d p = vg::parse_point(point);
    std::uint32_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < eyes.size(); ++i)
      if ((eyes[i] - p).squaredNorm() < best_d) best_d = (eyes[i] - p).squaredNorm(), best = static_cast<std::uint32_t>(i);
    out.push_back(best);
  }
  return out;
}
}  // namespace

void add_space_syntax_options(CLI::App* vgc, SpaceSyntaxArguments& a) {
  vgc->add_option("--measures", a.measures,
                  "space-syntax measures, comma-separated: connectivity, clustering, clustering-weighted, control, "
                  "controllability, mean-depth, integration, entropy, through-vision, metric, component, step-depth, "
                  "or all; columns MEASURE:CONDITION, e.g. integration_hh:fog:advection");
  vgc->add_option("--radius", a.radius, "steps for mean depth, integration and entropy: n (every step) or K")
      ->capture_default_str();
  vgc->add_option("--contrast-threshold", a.contrast_threshold,
                  "space syntax: keep the lines of sight whose contrast exp(-sigma d) >= this, in [0, 1) "
                  "(0.02: Koschmieder's threshold of detection; 0: every line)")
      ->capture_default_str();
  vgc->add_option("--graph", a.graph,
                  "space syntax: how the lines of sight are held, auto (the smaller of N x N bits and CSR lists), "
                  "bit-rows or csr; the results are the same")
      ->capture_default_str();
  vgc->add_option("--depth-from", a.depth_from, "step-depth origins x,y,z[;x,y,z...] (each snapped to the nearest node)");
}

void check_space_syntax_arguments(const SpaceSyntaxArguments& a, bool with_targets, bool pruned) {
  if (!a.wanted()) {
    if (!a.depth_from.empty()) throw std::invalid_argument("--depth-from: give --measures step-depth as well");
    return;
  }
  const vg::MeasureSet measures = vg::parse_measures(a.measures);
  parse_radius(a.radius);
  graph_storage(a.graph);
  if (!(a.contrast_threshold >= 0 && a.contrast_threshold < 1))
    throw std::invalid_argument("--contrast-threshold: " + io::significant(a.contrast_threshold, 6) +
                                " is outside [0, 1)");
  if (with_targets)
    throw std::invalid_argument("--measures needs every pair of nodes: leave out --targets and --target-point");
  if (pruned)
    throw std::invalid_argument("--measures needs every line of sight: leave out --prune-below (--contrast-threshold "
                                "keeps the lines by contrast, exactly)");
  if (measures.has(vg::Measure::step_depth) != !a.depth_from.empty())
    throw std::invalid_argument("--measures step-depth and --depth-from go together");
}

vg::SpaceSyntaxOptions space_syntax_options(const SpaceSyntaxArguments& a, const std::vector<double>& sigmas,
                                            const std::vector<Eigen::Vector3d>& eyes, double grid_spacing,
                                            int threads) {
  vg::SpaceSyntaxOptions o;
  o.sigmas = sigmas;
  o.measures = vg::parse_measures(a.measures);
  o.radius = parse_radius(a.radius);
  o.contrast_threshold = a.contrast_threshold;
  o.storage = graph_storage(a.graph);
  o.grid_spacing = grid_spacing;
  o.threads = threads;
  if (!a.depth_from.empty()) o.depth_origins = origins(a.depth_from, eyes);
  if (o.measures.has(vg::Measure::through_vision) && !(grid_spacing > 0))
    throw std::invalid_argument("--measures through-vision walks the node grid's cells: with --nodes give the "
                                "grid's --spacing");
  o.share = space_syntax_share();
  return o;
}

vg::GraphStorage graph_storage(const std::string& text) {
  vg::GraphStorage storage = vg::GraphStorage::automatic;
  if (!vg::parse_graph_storage(text, storage))
    throw std::invalid_argument("--graph: expected auto, bit-rows or csr, got '" + text + "'");
  return storage;
}

void check_space_syntax_memory(const vg::SpaceSyntaxEstimate& estimate, std::size_t nodes, bool allow_large) {
  const double memory = vg::physical_memory_bytes();
  const std::string refusal = vg::space_syntax_refusal(estimate, allow_large ? memory : 0.5 * memory, nodes);
  if (!refusal.empty())
    throw std::invalid_argument(refusal + (allow_large ? "" : " (--allow-large allows up to all of the machine's memory)"));
}

}  // namespace attenuvis::cli
