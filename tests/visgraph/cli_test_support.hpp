// Running the attenuvis program from tests, and reading what it writes:
// shared by the CLI tests of the visgraph module.
#pragma once

#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "../cli_run.hpp"

namespace clitest {

namespace fs = std::filesystem;

using Run = cli_run::Result;
using cli_run::run;

// A fresh empty directory, removed at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("attenuvis-vg-cli-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  // Names of the files in the directory (to prove nothing was left behind).
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path)) names.push_back(entry.path().filename().string());
    return names;
  }
};

inline std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(line);
  std::string part;
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    FAIL("no column " << name);
    return 0;
  }
};

inline Csv read_csv(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  Csv csv;
  std::string line;
  REQUIRE(std::getline(in, line));
  csv.header = split(line, ',');
  while (std::getline(in, line)) {
    std::vector<double> row;
    for (const std::string& cell : split(line, ',')) row.push_back(std::stod(cell));
    REQUIRE(row.size() == csv.header.size());
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace clitest
