// The build facts come from CMake (apps/CMakeLists.txt) as compile
// definitions; Boost's from its own header.
#include "build_info.hpp"

#include <boost/version.hpp>

#include "attenuvis/weather/refractive_index.hpp"

namespace attenuvis::cli {

std::string build_info() {
  // BOOST_VERSION is MAJOR * 100000 + MINOR * 100 + PATCH (boost/version.hpp).
  const std::string boost = std::to_string(BOOST_VERSION / 100000) + "." + std::to_string(BOOST_VERSION / 100 % 1000) +
                            "." + std::to_string(BOOST_VERSION % 100);
  return std::string("attenuvis ") + ATTENUVIS_VERSION + "\n" +
         "commit:     " + ATTENUVIS_GIT_COMMIT + " (at configure time)\n" +
         "build type: " + ATTENUVIS_BUILD_TYPE + "\n" +
         "Embree:     " + ATTENUVIS_EMBREE_VERSION + "\n" +
         "Boost:      " + boost + "\n" +
         "data:       " + weather::data_directory() + "\n";  // where the refractive-index tables are read
}

}  // namespace attenuvis::cli
