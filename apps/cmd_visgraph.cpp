// Placeholder: the visgraph subcommand(s) arrive with their issue.
#include "commands.hpp"

namespace attenuvis::cli {
void register_visgraph(CLI::App& /*app*/) {}
}  // namespace attenuvis::cli
