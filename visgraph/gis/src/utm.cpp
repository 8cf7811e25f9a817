// UTM zones (utm.hpp).
#include <attenuvis/visgraph/gis/utm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace attenuvis::visgraph::gis {

std::string utm_zone(double lon, double lat) {
  const int zone = std::clamp(static_cast<int>(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
  const bool north = lat >= 0;
  char text[64];
  std::snprintf(text, sizeof text, "UTM zone %d%c (EPSG:%d)", zone, north ? 'N' : 'S', (north ? 32600 : 32700) + zone);
  return text;
}

}  // namespace attenuvis::visgraph::gis
