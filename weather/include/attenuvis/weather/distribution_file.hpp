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
// bins must not overlap, the total must be > 0, and every value must lie in
// its domain (domains.hpp, in SI): radii domain::drop_radius, dN/dr
// domain::density_per_radius, dN/dln r and counts domain::number_per_volume.
// A UTF-8 byte-order mark is skipped.  The file must be a regular file of at
// most 16 MiB, a line at most 4096 characters.  Every error (std::invalid_argument)
// names the file and line.
#pragma once

#include <istream>
#include <string>

#include "attenuvis/weather/size_distribution.hpp"

namespace attenuvis::weather {

// Reads a size-distribution CSV (format above); errors name the file and line.
SizeDistribution read_distribution_csv(const std::string& path);
// `source` names the stream in error messages.
SizeDistribution read_distribution_csv(std::istream& in, const std::string& source);

// The grammar above as text (for error messages and --help).
const char* distribution_file_format();

}  // namespace attenuvis::weather
