// Reading a user's size distribution from a CSV file.
//
// Lines starting with '#' and blank lines are ignored.  The first other line
// is a header whose column names state the units; then one row per point/bin.
//
//   points, density per radius:      radius_um,dNdr_per_cm3_per_um     (or radius_m / radius_mm,
//                                                                       dNdr_per_m3_per_m)
//   points, density per ln radius:   radius_um,dNdlnr_per_cm3          (or dNdlnr_per_m3)
//   bins, counts:                    radius_lo_um,radius_hi_um,count_per_cm3   (or _m / _mm, count_per_m3)
//
// Point tables are joined by straight lines in n(r) = dN/dr (dN/dln r is
// converted point by point, n = (dN/dln r)/r) and are zero outside the first
// and last radius; they need at least two points.  Bins have n(r) constant
// inside each bin (count / width); one bin is enough.  Radii must increase,
// bins must not overlap, values must be finite and >= 0, and the total must be
// > 0.  Every error names the file and line.
#pragma once

#include <istream>
#include <string>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

SizeDistribution read_distribution_csv(const std::string& path);
// `source` names the stream in error messages.
SizeDistribution read_distribution_csv(std::istream& in, const std::string& source);

// The grammar above as text (for error messages and --help).
const char* distribution_file_format();

}  // namespace attenuvis::weather
