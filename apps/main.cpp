// attenuvis: command-line entry point.  Every failure, CLI11's own included,
// is reported the same way: "attenuvis: error: WHAT" on stderr and a non-zero
// exit status.
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <string>

#include "build_info.hpp"
#include "commands.hpp"

namespace attenuvis::cli {
int& exit_status() {
  static int status = 0;
  return status;
}

namespace {

// CLI11's own message with every word longer than 60 characters cut (a
// 300-digit number echoed by its range check should not fill the terminal).
// Only CLI11's messages: the libraries' messages name files, which are shown whole.
std::string shortened(const std::string& message) {
  std::string out, word;
  const auto flush = [&] {
    if (word.size() > 60) word = word.substr(0, 40) + "...(" + std::to_string(word.size()) + " characters)";
    out += word;
    word.clear();
  };
  for (char c : message) {
    if (c == ' ' || c == '\n') {
      flush();
      out += c;
    } else {
      word += c;
    }
  }
  flush();
  return out;
}

std::string error_line(const std::string& what) { return "attenuvis: error: " + what + "\n"; }

}  // namespace
}  // namespace attenuvis::cli

int main(int argc, char** argv) {
  using attenuvis::cli::error_line;
  using attenuvis::cli::shortened;
  CLI::App app{"attenuvis: Lorenz-Mie reference, ITU-R P.1817 attenuation and weather-weighted visibility graphs"};
  app.require_subcommand(1);
  // CLI11 prints the text to stdout and exits 0; the trailing newline is its own.
  std::string version = attenuvis::cli::build_info();
  version.pop_back();
  app.set_version_flag("--version", version, "print the version and build (commit, build type, Embree, Boost)");
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return error_line(shortened(e.what()) + " (--help lists the options)");
  });
  attenuvis::cli::register_mie(app);
  attenuvis::cli::register_weather(app);
  attenuvis::cli::register_visgraph(app);
  attenuvis::cli::register_scene_command(app);
  attenuvis::cli::register_reproduce(app);
  attenuvis::cli::register_optics(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::bad_alloc&) {
    std::cerr << error_line("out of memory: the input asks for more than this machine can hold");
    return 1;
  } catch (const std::exception& e) {
    std::cerr << error_line(e.what());
    return 1;
  }
  return attenuvis::cli::exit_status();
}
