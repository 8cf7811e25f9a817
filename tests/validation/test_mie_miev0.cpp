// Loading Wiscombe's MIEV0 for the optional speed comparison
// (attenuvis/validation/mie_miev0.hpp): a library that cannot be used is a
// clear error naming the file, before any timing.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "attenuvis/validation/mie_miev0.hpp"

using attenuvis::validation::Miev0Library;

TEST_CASE("MIEV0 comparison: a missing library is an error naming the file", "[validation]") {
  const std::string path = "/nonexistent/attenuvis-test/libmiev0.so";
  try {
    Miev0Library lib(path);
    FAIL("no error for a missing library");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("cannot load the MIEV0 library") && Catch::Contains(path));
  }
}

TEST_CASE("MIEV0 comparison: a library without MIEV0 is an error naming the file and the build script",
          "[validation]") {
  // glibc's libm: loadable, but with no miev0_.
  try {
    Miev0Library lib("libm.so.6");
    FAIL("no error for a library without miev0_");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("libm.so.6") && Catch::Contains("has no miev0_") &&
                         Catch::Contains("build_miev0.sh"));
  }
}
