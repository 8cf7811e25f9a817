// Range checks of limits.hpp.
#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/number_text.hpp>

#include <cmath>
#include <stdexcept>

namespace attenuvis::visgraph {

void check_coordinate(double value, const std::string& where) {
  if (std::isfinite(value) && std::abs(value) <= kMaxCoordinate) return;
  throw std::invalid_argument(where + ": coordinate " + io::significant(value, 6) +
                              " is outside [-1e7, 1e7] m (the range attenuvis vg accepts: UTM-sized "
                              "coordinates; shift larger ones)");
}

void check_range(double value, double lo, double hi, const std::string& what, const std::string& unit) {
  if (std::isfinite(value) && value >= lo && value <= hi) return;
  throw std::invalid_argument(what + ": " + io::significant(value, 6) + " is outside [" + io::shortest(lo) + ", " +
                              io::shortest(hi) + "]" + (unit.empty() ? "" : " " + unit));
}

}  // namespace attenuvis::visgraph
