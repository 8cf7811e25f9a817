// attenuvis: command-line entry point.  Errors are reported as one line on
// stderr, prefixed with "attenuvis: error:", and give a non-zero exit status.
#include <exception>
#include <iostream>

#include "commands.hpp"

namespace attenuvis::cli {
int& exit_status() {
  static int status = 0;
  return status;
}
}  // namespace attenuvis::cli

int main(int argc, char** argv) {
  CLI::App app{"attenuvis: Lorenz-Mie reference, ITU-R P.1817 attenuation and weather-weighted visibility graphs"};
  app.require_subcommand(1);
  attenuvis::cli::register_mie(app);
  attenuvis::cli::register_weather(app);
  attenuvis::cli::register_visgraph(app);
  attenuvis::cli::register_scene_command(app);
  attenuvis::cli::register_reproduce(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "attenuvis: error: " << e.what() << "\n";
    return 1;
  }
  return attenuvis::cli::exit_status();
}
