// Subcommand registration for the attenuvis program.  Each subcommand lives in
// its own apps/cmd_*.cpp file, parses its arguments with CLI11 and calls the
// libraries; it never computes anything itself.
#pragma once

#include <CLI/CLI.hpp>

namespace attenuvis::cli {

// Exit status the program returns after a successful parse.  A subcommand
// that finishes its work but saw bad input (e.g. a malformed batch line) sets
// it to a non-zero value instead of throwing, so the good work is kept.
int& exit_status();

void register_mie(CLI::App& app);          // cmd_mie.cpp
void register_weather(CLI::App& app);      // cmd_weather.cpp: sigma, table, distribution
void register_visgraph(CLI::App& app);     // cmd_visgraph.cpp: vg
void register_scene_command(CLI::App& app);  // cmd_scene.cpp: scene
void register_reproduce(CLI::App& app);    // cmd_reproduce.cpp
void register_optics(CLI::App& app);       // cmd_optics.cpp: optics

}  // namespace attenuvis::cli
