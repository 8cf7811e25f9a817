// What `--help` shows for every subcommand, written once for all of them: a
// one-line summary (the subcommand's description), its options in named
// groups, and a footer that points to the subcommand's page of the user guide
// instead of repeating long grammar.  The grammar itself stays one command
// away (`attenuvis help conditions`), printed from the weather registries.
// Also the validators whose messages state a range as a person writes it.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace attenuvis::cli {

// Applies the groups and the guide footer of help_layouts() to every
// subcommand of `app` and the documentation footer to `app` itself.  Called
// once, after every subcommand is registered, so a subcommand file only adds
// its options; an option no layout names stays under "Options".
void apply_help_layout(CLI::App& app);

// `attenuvis help [TOPIC]`: the condition grammar, the size-distribution file
// format and the valid ranges, and where the documentation is.
void register_help(CLI::App& app);

// Where the HTML documentation is: the installed copy
// (<prefix>/share/doc/attenuvis/html), else the build tree's, else the
// Markdown sources (docs/ in the source tree).
std::string documentation_location();

// Validators for numeric options whose failure reads "must be >= 0" or
// "must be in [0, 1024]" (CLI11's own print the limits of a double in full).
CLI::Validator at_least(double lo);
CLI::Validator in_range(double lo, double hi);

}  // namespace attenuvis::cli
