// The rows of a CSV table in tests/data/mie ('#' comments and the header line
// skipped), each as its cells' text: the published digits stay as printed.
#pragma once

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mie_test {

inline std::vector<std::vector<std::string>> read_csv_rows(const std::string& name) {
  std::ifstream in(std::string(ATTENUVIS_TEST_DATA_DIR) + "/mie/" + name);
  REQUIRE(in);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<std::string> row;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace mie_test
