// The UTM zone to suggest for data given in degrees.
#pragma once

#include <string>

namespace attenuvis::visgraph::gis {

// The zone of the Universal Transverse Mercator system that holds longitude
// `lon` (degrees east, [-180, 180]), north or south of the equator by `lat`:
// zone = floor((lon + 180) / 6) + 1 (1..60; 180 degrees east is zone 60),
// EPSG:326zz (WGS 84 / UTM zone zzN) or EPSG:327zz (zzS).  The exceptions
// around Norway and Svalbard are not applied: any zone whose central
// meridian is within 3 degrees keeps scale distortion under 1 part in 1000.
// Returns "UTM zone 32N (EPSG:32632)"; a longitude outside [-180, 180] is
// taken at the nearest end.
std::string utm_zone(double lon, double lat);

}  // namespace attenuvis::visgraph::gis
