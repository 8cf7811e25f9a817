// UTM zones (utm.hpp).
#include <attenuvis/visgraph/gis/utm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace attenuvis::visgraph::gis {

std::string utm_zone(double lon, double lat) {
  // Clamped before the conversion: a longitude outside [-180, 180] (or NaN)
  // names the nearest edge zone rather than overflowing an int.
  const double clamped = std::isnan(lon) ? 0.0 : std::clamp(lon, -180.0, 180.0);
  const int zone = std::clamp(static_cast<int>(std::floor((clamped + 180.0) / 6.0)) + 1, 1, 60);
  const bool north = lat >= 0;
  char text[64];
  std::snprintf(text, sizeof text, "UTM zone %d%c (EPSG:%d)", zone, north ? 'N' : 'S', (north ? 32600 : 32700) + zone);
  return text;
}

}  // namespace attenuvis::visgraph::gis
