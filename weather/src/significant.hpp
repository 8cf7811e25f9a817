// A number in text with a given count of significant digits, for the error
// messages and method notes of the weather module (bulk_optics.cpp,
// contour_extinction.cpp, sigma.cpp).
#pragma once

#include <sstream>
#include <string>

namespace attenuvis::weather::detail {

inline std::string significant(double v, int digits) {
  std::ostringstream o;
  o.precision(digits);
  o << v;
  return o.str();
}

}  // namespace attenuvis::weather::detail
