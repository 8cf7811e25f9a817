// Placeholder: the mie subcommand(s) arrive with their issue.
#include "commands.hpp"

namespace attenuvis::cli {
void register_mie(CLI::App& /*app*/) {}
}  // namespace attenuvis::cli
