// Private to the reproduction job: attenuvis::mie against the published Mie
// tables of tests/data/mie/*.csv (each file carries its citation), with the
// same tolerance rule as tests/mie/test_mie_published.cpp:
//   * a printed real number is matched if it lies within half a unit of its
//     last printed digit;
//   * a printed complex number gets, in both parts, the half unit of its
//     larger part (the source rounded both parts relative to the larger one);
//   * entries where the SOURCE is not exact to the digits it prints (its own
//     small-particle formulas, Wiscombe's term count, single precision) are
//     listed with the reason in documented_inaccuracies.csv beside the tables and
//     must still agree to the accuracy that method delivers.
// Nothing here is tuned to the results: the rule and the list are the test's.
#pragma once

#include <string>
#include <vector>

namespace attenuvis::validation::detail {

// One compared number.
struct PublishedEntry {
  std::string source;     // key of the source, e.g. "miev0" (see PublishedSource)
  std::string row;        // case number, label or angle, as the table names it
  std::string quantity;   // e.g. "qext", "s1@30"
  std::string parameters; // "x = 10, m = 1.5+0.1i"
  std::string published;  // as printed (complex: "(re, im)" in the attenuvis convention)
  std::string computed;   // attenuvis, 10 significant digits
  double abs_diff = 0;    // |computed - published| (complex: the larger part difference)
  double half_unit = 0;   // half a unit in the last printed digit
  double rel_error = 0;   // |computed - published| / |published| (complex: modulus)
  bool within_digits = false;
  std::string documented; // reason the source itself is off ("" when none applies)
  double documented_rel = 0;  // accuracy that reason allows (relative)
  bool ok() const { return within_digits || (!documented.empty() && rel_error <= documented_rel); }
  double units() const { return half_unit > 0 ? abs_diff / (2 * half_unit) : 0; }  // in last-digit units
};

struct PublishedSource {
  std::string key;        // "miev0", "w79", "w79s", "bh", "du1", "du2"
  std::string title;      // e.g. "Wiscombe MIEV0 test cases 1-19 (Qext, ...)"
  std::string short_name; // for figure legends, e.g. "Wiscombe MIEV0 cases"
  std::string citation;   // publication, table / page
  std::string file;       // data file name under the tables directory
  std::string digits;     // what the source states about its digits
};

struct PublishedComparison {
  std::string tables_dir;
  std::vector<PublishedSource> sources;
  std::vector<PublishedEntry> entries;
};

// The directory holding the published tables: tests/data/mie of the source
// tree this library was configured from (the report needs it on a clean clone;
// the test suite reads the same files).
std::string published_tables_dir();

// Reads every table and compares it with attenuvis::mie.  Throws
// std::runtime_error naming the file when a table cannot be read.
PublishedComparison compare_published_mie(const std::string& tables_dir);

}  // namespace attenuvis::validation::detail
