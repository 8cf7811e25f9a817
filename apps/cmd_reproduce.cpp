// `attenuvis reproduce [--out DIR] [--quick] [--threads N]`: the main job.
// Parses arguments and calls attenuvis::validation::reproduce(); prints the
// one-screen summary on stdout (progress goes to stderr).
#include <iostream>
#include <memory>

#include "attenuvis/validation/reproduce.hpp"
#include "commands.hpp"

namespace attenuvis::cli {

void register_reproduce(CLI::App& app) {
  auto options = std::make_shared<validation::ReproduceOptions>();
  auto* cmd = app.add_subcommand(
      "reproduce", "Reproduce the seed paper's tables and figures and the Mie validation into DIR/report.html");
  cmd->add_option("--out", options->out_dir, "Output directory (created if missing)")->capture_default_str();
  cmd->add_flag("--quick", options->quick, "Small version: coarse grids, small city, few Mie points (for tests)");
  cmd->add_option("--threads", options->threads, "Threads to use (0 = all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->callback([options]() {
    options->progress = &std::cerr;
    const auto result = validation::reproduce(*options);
    for (const auto& line : result.summary) std::cout << line << "\n";
    std::cout.flush();
  });
}

}  // namespace attenuvis::cli
