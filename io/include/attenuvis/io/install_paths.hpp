// Where the files that go with the program live: the installed copy
// (<prefix>/share/attenuvis, written by `cmake --install`) when the running
// program or the loaded Python extension sits under such a prefix, else the
// source tree the build was configured from.  One search for every module's
// data (refractive-index tables, figure scripts, published reference tables).
#pragma once

#include <string>

namespace attenuvis::io {

// <prefix>/share/attenuvis above the object this library was loaded from
// (the installed extension module, or the program itself via
// /proc/self/exe), at most four directories up; "" when there is none.
// Found once and remembered.
const std::string& installed_share_directory();

// <prefix>/share/doc/attenuvis/html beside that share directory (where
// `cmake --install` puts the HTML documentation) when it holds an index.html;
// "" otherwise.
std::string installed_documentation_directory();

// installed_share_directory()/relative when that exists, else source_path.
std::string installed_or_source(const std::string& relative, const std::string& source_path);

}  // namespace attenuvis::io
