#include "attenuvis/io/shell.hpp"

namespace attenuvis::io {

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

}  // namespace attenuvis::io
