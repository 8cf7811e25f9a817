// `attenuvis vg --measures ...`: the space-syntax options of the vg
// subcommand, read into visgraph::SpaceSyntaxOptions (visgraph/space_syntax.hpp).
#pragma once

#include <attenuvis/visgraph/space_syntax.hpp>

#include <CLI/CLI.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace attenuvis::cli {

struct SpaceSyntaxArguments {
  std::string measures;              // empty: no space syntax
  std::string radius = "n";          // n or a number of steps
  double contrast_threshold = visgraph::kKoschmiederContrast;
  std::string depth_from;            // step-depth origins: x,y,z[;x,y,z...]
  std::string graph = "auto";        // auto, bit-rows or csr
  bool wanted() const { return !measures.empty(); }
};

void add_space_syntax_options(CLI::App* vg, SpaceSyntaxArguments& a);

// Refuses, before any work, values out of range and space syntax with
// targets or pruning (it needs every line of sight).
void check_space_syntax_arguments(const SpaceSyntaxArguments& a, bool with_targets, bool pruned);

// The options for the pass's conditions and nodes; `grid_spacing` is the
// node grid's (0 for nodes from a file: through vision then needs --spacing).
visgraph::SpaceSyntaxOptions space_syntax_options(const SpaceSyntaxArguments& a, const std::vector<double>& sigmas,
                                                  const std::vector<Eigen::Vector3d>& eyes, double grid_spacing,
                                                  int threads);

// auto, bit-rows or csr as a GraphStorage (throws naming --graph otherwise).
visgraph::GraphStorage graph_storage(const std::string& text);

// Refuses a run whose graph would not fit (half the machine's memory, all of
// it with --allow-large), with the numbers and what to change.
void check_space_syntax_memory(const visgraph::SpaceSyntaxEstimate& estimate, std::size_t nodes, bool allow_large);

}  // namespace attenuvis::cli
