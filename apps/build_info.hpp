// What `attenuvis --version` prints: the program's version and the build it
// came from (commit, build type, and the Embree and Boost it was compiled
// against), so that a published figure can name the exact code behind it.
#pragma once

#include <string>

namespace attenuvis::cli {

// Several lines, "attenuvis 0.1.0" first, ending with a newline.
std::string build_info();

}  // namespace attenuvis::cli
