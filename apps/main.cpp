// attenuvis: command-line entry point.  Every failure, CLI11's own included,
// is reported the same way: "attenuvis: error: WHAT" on stderr and a non-zero
// exit status.  Started by mpirun on several processes, a failure on any of
// them ends all of them (process_group.hpp).
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <string>

#include "build_info.hpp"
#include "command_help.hpp"
#include "commands.hpp"
#include "process_group.hpp"

namespace attenuvis::cli {
int run_program(int argc, char** argv);

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

// The message on stderr and status 1; on several processes, every one of
// them ends (a process that failed alone would leave the others waiting).
int fail(const std::string& message) {
  if (process_count() > 1) {
    const std::string where = "process " + std::to_string(process_rank()) + " of " + std::to_string(process_count());
    abort_process_group(message.substr(0, message.size() - 1) + " (" + where + ")\n");
  }
  std::cerr << message;
  return 1;
}

}  // namespace
}  // namespace attenuvis::cli

int main(int argc, char** argv) {
  attenuvis::cli::start_process_group(&argc, &argv);
  const int status = attenuvis::cli::run_program(argc, argv);
  attenuvis::cli::finish_process_group();
  return status;
}

int attenuvis::cli::run_program(int argc, char** argv) {
  using attenuvis::cli::error_line;
  using attenuvis::cli::fail;
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
#ifndef ATTENUVIS_WITHOUT_REPRODUCE
  attenuvis::cli::register_reproduce(app);
#endif
  attenuvis::cli::register_optics(app);
  attenuvis::cli::register_help(app);
  attenuvis::cli::apply_help_layout(app);
  // Only `vg` shares its work; any other command on several processes would
  // do the same work on each and write the same files.
  if (attenuvis::cli::process_count() > 1 && (argc < 2 || std::string(argv[1]) != "vg"))
    return attenuvis::cli::fail(error_line("only `attenuvis vg` runs on several processes (mpirun -np " +
                                           std::to_string(attenuvis::cli::process_count()) +
                                           "); run this command as one process"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != 0 && attenuvis::cli::process_count() > 1) {
      // Every process parsed the same arguments; one message is enough.
      if (attenuvis::cli::is_root_process()) app.exit(e);
      attenuvis::cli::abort_process_group("");
    }
    return app.exit(e);
  } catch (const std::bad_alloc&) {
    return fail(error_line("out of memory: the input asks for more than this machine can hold"));
  } catch (const std::exception& e) {
    return fail(error_line(e.what()));
  }
  return attenuvis::cli::exit_status();
}
