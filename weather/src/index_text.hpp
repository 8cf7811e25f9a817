// The text pieces the index-file readers share (index_file.cpp, index_yaml.cpp,
// opac_data.cpp): trimming, splitting a row into its numbers, and reading a
// number with the file and line in the message.
#pragma once

#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/io/number_text.hpp"

namespace attenuvis::weather::detail {

inline std::string trimmed(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

// The fields of a row separated by blanks, tabs or commas.
inline std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : row) {
    if (std::isspace(static_cast<unsigned char>(ch)) || ch == ',') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += ch;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

// A finite number, or std::runtime_error "WHERE: WHAT 'TEXT' is not a number".
inline double number(const std::string& text, const std::string& where, const std::string& what) {
  try {
    return io::parse_double(text, what);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(where + ": " + e.what());
  }
}

}  // namespace attenuvis::weather::detail
