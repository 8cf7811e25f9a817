// Placeholder: the reproduce subcommand(s) arrive with their issue.
#include "commands.hpp"

namespace attenuvis::cli {
void register_reproduce(CLI::App& /*app*/) {}
}  // namespace attenuvis::cli
