// Running the attenuvis program (ATTENUVIS_CLI) from the tests of every module.
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include <sys/wait.h>

namespace cli_run {

struct Result {
  int status;
  std::string output;  // stdout + stderr
};

inline Result run(const std::string& args) {
  const std::string command = std::string(ATTENUVIS_CLI) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe.get())) out += buffer.data();
  const int raw = pclose(pipe.release());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

}  // namespace cli_run
