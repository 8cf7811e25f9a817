// Output paths checked before any work: two outputs on one file, or an
// output over one of the run's inputs, would lose data whichever is written
// last, so such a run is refused up front.
#pragma once

#include <string>
#include <vector>

namespace attenuvis::cli {

// One path of the run and what names it ("--out", "fog:file=").
struct NamedPath {
  std::string what;
  std::string path;
};

// Throws std::invalid_argument when two outputs name the same file, or an
// output names an input (compared after resolving '.', '..' and symbolic
// links).  Empty paths (options not given) are skipped.
void refuse_path_clashes(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

}  // namespace attenuvis::cli
