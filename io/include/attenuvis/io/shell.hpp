// Quoting for /bin/sh command lines (the figure scripts are run through it).
#pragma once

#include <string>

namespace attenuvis::io {

// 'text' with every single quote written as '\'' : safe for any byte string.
std::string shell_quote(const std::string& text);

}  // namespace attenuvis::io
