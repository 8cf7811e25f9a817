// GDAL set-up, messages and CRS helpers (gdal_support.hpp).
#include "gdal_support.hpp"

#include <attenuvis/visgraph/gis/utm.hpp>

#include <attenuvis/io/number_text.hpp>

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <mutex>
#include <stdexcept>

namespace attenuvis::visgraph::gis::detail {

void register_gdal() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

GdalMessages::GdalMessages() { CPLPushErrorHandlerEx(&GdalMessages::handler, this); }
GdalMessages::~GdalMessages() { CPLPopErrorHandler(); }

void CPL_STDCALL GdalMessages::handler(CPLErr level, CPLErrorNum /*code*/, const char* text) {
  auto* self = static_cast<GdalMessages*>(CPLGetErrorHandlerUserData());
  if (self && level >= CE_Failure && text) self->last_ = text;
}

std::string GdalMessages::because() const { return last_.empty() ? "" : ": " + last_; }

std::string crs_label(const OGRSpatialReference* srs) {
  if (!srs || srs->IsEmpty()) return "";
  OGRSpatialReference copy(*srs);
  const char* authority = copy.GetAuthorityName(nullptr);
  if (!authority) {
    copy.AutoIdentifyEPSG();
    authority = copy.GetAuthorityName(nullptr);
  }
  const char* code = copy.GetAuthorityCode(nullptr);
  if (authority && code) return std::string(authority) + ":" + code;
  const char* name = srs->GetName();
  return name ? name : "an unnamed CRS";
}

std::string crs_text(const OGRSpatialReference* srs) {
  if (!srs || srs->IsEmpty()) return "";
  const std::string label = crs_label(srs);
  if (label.rfind("EPSG:", 0) == 0) return label;
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", "MULTILINE=NO", nullptr};
  if (srs->exportToWkt(&wkt, options) != OGRERR_NONE || !wkt) {
    CPLFree(wkt);
    return label;
  }
  std::string text = wkt;
  CPLFree(wkt);
  return text;
}

bool parse_crs(const std::string& text, OGRSpatialReference& srs) {
  if (text.empty()) return false;
  GdalMessages quiet;
  // SET_FROM_USER_INPUT_LIMITATIONS: no file names, no URLs fetched.
  return srs.SetFromUserInput(text.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS) == OGRERR_NONE;
}

bool same_horizontal_crs(const std::string& model, const OGRSpatialReference& other) {
  OGRSpatialReference a;
  if (!parse_crs(model, a)) return model == crs_label(&other);
  OGRSpatialReference b(other);
  GdalMessages quiet;
  if (a.IsCompound()) a.StripVertical();
  if (b.IsCompound()) b.StripVertical();
  const char* criteria[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES", "CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS",
                            nullptr};
  return a.IsSame(&b, criteria);
}

namespace {
// Longitude and latitude of a point given in `srs`, or false.
bool to_lonlat(const OGRSpatialReference& srs, double x, double y, double& lon, double& lat) {
  OGRSpatialReference source(srs), wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  GdalMessages quiet;
  std::unique_ptr<OGRCoordinateTransformation> to(OGRCreateCoordinateTransformation(&source, &wgs84));
  if (!to || !to->Transform(1, &x, &y)) return false;
  lon = x;
  lat = y;
  return std::abs(lon) <= 180 && std::abs(lat) <= 90;  // false for NaN too
}
}  // namespace

void require_metres(const OGRSpatialReference& srs, const std::string& what, double centre_x, double centre_y) {
  const bool geographic = srs.IsGeographic();
  const char* unit = nullptr;
  const double metres_per_unit = geographic ? 0.0 : srs.GetLinearUnits(&unit);
  if (!geographic && std::abs(metres_per_unit - 1.0) < 1e-9) return;
  double lon = 0, lat = 0;
  std::string zone;
  if (to_lonlat(srs, centre_x, centre_y, lon, lat)) zone = ", e.g. " + utm_zone(lon, lat) + " for its extent";
  const std::string in = geographic ? "degrees" : std::string(unit ? unit : "units") + " of " +
                                                      io::significant(metres_per_unit, 6) + " m";
  throw std::invalid_argument(what + " is in " + crs_label(&srs) + ", measured in " + in +
                              ": a projected CRS in metres is needed" + zone +
                              " (reproject it, e.g. ogr2ogr -t_srs or gdalwarp -t_srs)");
}

}  // namespace attenuvis::visgraph::gis::detail
