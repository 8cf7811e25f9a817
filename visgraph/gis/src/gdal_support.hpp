// What the GDAL-facing readers and writers share: GDAL's drivers registered
// once, GDAL's messages kept from stderr and turned into ours, and the CRS
// names and checks they all make.  Internal to attenuvis::visgraph_gis.
#pragma once

#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <string>

namespace attenuvis::visgraph::gis::detail {

// Registers GDAL's drivers (once per process).
void register_gdal();

// While one lives, GDAL's errors and warnings on this thread are kept here
// instead of being printed; last() is the most recent failure's text.
class GdalMessages {
 public:
  GdalMessages();
  ~GdalMessages();
  GdalMessages(const GdalMessages&) = delete;
  GdalMessages& operator=(const GdalMessages&) = delete;
  // ": WHY" when GDAL said why something failed, "" otherwise.
  std::string because() const;

 private:
  static void CPL_STDCALL handler(CPLErr level, CPLErrorNum code, const char* text);
  std::string last_;
};

// "EPSG:32632" when the CRS has an EPSG code (found from its definition if it
// names none), else its name; "" for none.
std::string crs_label(const OGRSpatialReference* srs);
// The CRS as a Mesh stores it (mesh.hpp): "EPSG:N" when it has an EPSG code,
// else its WKT2 definition; "" for none.
std::string crs_text(const OGRSpatialReference* srs);
// A CRS from the text a model names (an EPSG code, a URN, a URL, WKT):
// false when it is none of these.  Never reads a file or the network.
bool parse_crs(const std::string& text, OGRSpatialReference& srs);

// True when `model` (as Mesh::crs holds it) and `other` name the same
// horizontal CRS: a compound CRS's vertical part is left out, and axis
// order does not count.  A model CRS GDAL does not know is compared by its
// label.
bool same_horizontal_crs(const std::string& model, const OGRSpatialReference& other);

// Throws std::invalid_argument unless the CRS measures horizontal
// coordinates in metres: a geographic CRS (degrees) or a projected one in
// feet is refused, naming `what`, the CRS and the UTM zone (utm.hpp) of the
// extent's centre (given in the CRS's own coordinates, x = easting or
// longitude).
void require_metres(const OGRSpatialReference& srs, const std::string& what, double centre_x, double centre_y);

}  // namespace attenuvis::visgraph::gis::detail
