// A failed internal check (check.hpp).
#include "attenuvis/io/check.hpp"

#include <cstdlib>
#include <iostream>

namespace attenuvis::io {

std::string check_failure_text(const char* file, int line, const char* expression, const std::string& values) {
  std::string out = std::string("attenuvis: internal check failed at ") + file + ":" + std::to_string(line) + ": " +
                    expression;
  if (!values.empty()) out += " (" + values + ")";
  return out;
}

void check_failed(const char* file, int line, const char* expression, const std::string& values) {
  std::cerr << check_failure_text(file, line, expression, values)
            << "\nThis is a bug in attenuvis, not in the input; please report it with the command that led here."
            << std::endl;
  std::abort();
}

}  // namespace attenuvis::io
