// Placeholder: the weather subcommand(s) arrive with their issue.
#include "commands.hpp"

namespace attenuvis::cli {
void register_weather(CLI::App& /*app*/) {}
}  // namespace attenuvis::cli
