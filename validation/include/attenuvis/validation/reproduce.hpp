// `attenuvis reproduce`: rebuilds the seed paper's tables and figures
// (Schwartz, Vinnikov & Federici, SimAUD 2021) and the validation against
// published Mie data, computed in this run, into one HTML report.
//
// Output directory layout (all written at the end, report.html last):
//   report.html   self-contained page (inline CSS), figures referenced beside it
//   <table>.csv   every table of the report
//   <figure>.png  every figure (matplotlib, Debian's /usr/bin/python3)
//   key.json      the named key numbers (also returned in ReproduceResult)
// Work happens in a staging directory inside `out_dir`; if anything fails
// (a figure script, a section throwing) the staging directory is removed and
// reproduce() throws, so no report pretends to be complete.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "attenuvis/validation/report.hpp"

namespace attenuvis::validation {

// What `attenuvis reproduce` is asked for.
struct ReproduceOptions {
  std::string out_dir = "out";
  bool quick = false;          // small version for tests: coarse grids, small city, few Mie points
  int threads = 0;             // 0 = all cores TBB sees
  bool figures = true;         // false: skip matplotlib (tests that only check numbers)
  std::ostream* progress = nullptr;  // progress line (stderr in the CLI); nullptr = silent
  // Shared library of an earlier Mie core (validation/bench/baseline/
  // build_mie_baseline.sh, commit 78ee94c by default).  When given, the Mie
  // section times the current core against it in the same run; "" = no such
  // table (the section says how to get it).  A library that cannot be loaded
  // stops the job before any work, naming the file and the loader's message.
  std::string mie_baseline;
};

// What a reproduction wrote and found.
struct ReproduceResult {
  std::string report_path;                 // out_dir/report.html ("" when figures/report skipped)
  std::map<std::string, double> key;       // named key numbers (see key.json)
  std::vector<std::string> summary;        // the one-screen summary, line by line
  std::vector<std::string> missing;        // sections not available in this build
  double seconds = 0.0;
};

// Runs every section and writes the report.  Throws std::runtime_error with
// a message naming the failing step.
ReproduceResult reproduce(const ReproduceOptions& options);

}  // namespace attenuvis::validation
