// Running the attenuvis program (ATTENUVIS_CLI) from the weather tests.
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include <sys/wait.h>

namespace weather_cli {

struct Result {
  int status;
  std::string out;  // stdout + stderr
};

inline Result run(const std::string& args) {
  const std::string cmd = std::string(ATTENUVIS_CLI) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  const int raw = pclose(pipe.release());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

}  // namespace weather_cli
