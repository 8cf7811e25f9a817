// `attenuvis reproduce [--out DIR] [--quick] [--threads N] [--mie-baseline LIB]`: the main job.
// Parses arguments and calls attenuvis::validation::reproduce(); prints the
// one-screen summary on stdout (progress goes to stderr).
#include <iostream>
#include <memory>

#include "attenuvis/validation/reproduce.hpp"
#include "command_help.hpp"
#include "commands.hpp"

namespace attenuvis::cli {

void register_reproduce(CLI::App& app) {
  auto options = std::make_shared<validation::ReproduceOptions>();
  auto* cmd = app.add_subcommand(
      "reproduce", "Reproduce the seed paper's tables and figures and the Mie validation into DIR/report.html");
  cmd->add_option("--out", options->out_dir, "Output directory (created if missing)")->capture_default_str();
  cmd->add_flag("--quick", options->quick, "Small version: coarse grids, small city, few Mie points (for tests)");
  cmd->add_option("--threads", options->threads, "Threads to use (0 = all cores)")
      ->check(at_least(0))
      ->capture_default_str();
  // The last one given wins, so that `scripts/main.sh --mie-baseline OTHER`
  // overrides the library main.sh builds.
  cmd->add_option("--mie-baseline", options->mie_baseline,
                  "Shared library of an earlier Mie core (validation/bench/baseline/build_mie_baseline.sh): "
                  "adds its per-call and batch speed-up to the Mie section")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  cmd->callback([options]() {
    options->progress = &std::cerr;
    const auto result = validation::reproduce(*options);
    for (const auto& line : result.summary) std::cout << line << "\n";
    std::cout.flush();
  });
}

}  // namespace attenuvis::cli
