// GIS files written by the tests themselves through GDAL: a GeoTIFF DEM of a
// known surface and a layer of footprints (GeoPackage or GeoJSON) with
// height fields.
#pragma once

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <catch2/catch.hpp>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vgtest {

// A north-up Float32 GeoTIFF: `cols` x `rows` cells of `cell` metres, the
// top-left corner at (x0, y_top), each cell the surface at its centre; cells
// listed in `nodata` (column, row) hold the nodata value -9999.
inline void write_geotiff(const std::string& path, int epsg, double x0, double y_top, double cell, int cols, int rows,
                          const std::function<double(double, double)>& surface,
                          const std::vector<std::pair<int, int>>& nodata = {}) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  REQUIRE(driver);
  GDALDatasetUniquePtr ds(driver->Create(path.c_str(), cols, rows, 1, GDT_Float32, nullptr));
  REQUIRE(ds);
  double gt[6] = {x0, cell, 0, y_top, 0, -cell};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  ds->SetSpatialRef(&srs);
  std::vector<float> z(static_cast<std::size_t>(cols) * rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      z[static_cast<std::size_t>(r) * cols + c] = static_cast<float>(surface(x0 + (c + 0.5) * cell, y_top - (r + 0.5) * cell));
  for (const auto& [c, r] : nodata) z[static_cast<std::size_t>(r) * cols + c] = -9999.0f;
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-9999.0);
  REQUIRE(band->RasterIO(GF_Write, 0, 0, cols, rows, z.data(), cols, rows, GDT_Float32, 0, 0, nullptr) == CE_None);
}

using Ring = std::vector<std::array<double, 2>>;

struct TestFeature {
  std::vector<std::vector<Ring>> polygons;  // one polygon: a Polygon; more: a MultiPolygon
  std::optional<double> height, levels;
};

// An axis-aligned rectangle as a ring (counter-clockwise, closed).
inline Ring rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
}

// A layer "buildings" with fields height (Real) and levels (Integer), in
// EPSG:epsg (0: no CRS), through the GDAL driver named (GPKG, GeoJSON, ...).
inline void write_footprints(const std::string& path, const std::string& driver_name, int epsg,
                             const std::vector<TestFeature>& features) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name.c_str());
  REQUIRE(driver);
  GDALDatasetUniquePtr ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  REQUIRE(ds);
  OGRSpatialReference srs;
  if (epsg) srs.importFromEPSG(epsg);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = ds->CreateLayer("buildings", epsg ? &srs : nullptr, wkbUnknown, nullptr);
  REQUIRE(layer);
  OGRFieldDefn height("height", OFTReal), levels("levels", OFTInteger);
  REQUIRE(layer->CreateField(&height) == OGRERR_NONE);
  REQUIRE(layer->CreateField(&levels) == OGRERR_NONE);
  for (const TestFeature& f : features) {
    OGRFeature feature(layer->GetLayerDefn());
    OGRMultiPolygon multi;
    for (const auto& rings : f.polygons) {
      OGRPolygon polygon;
      for (const Ring& ring : rings) {
        OGRLinearRing r;
        for (const auto& p : ring) r.addPoint(p[0], p[1]);
        polygon.addRing(&r);
      }
      multi.addGeometry(&polygon);
    }
    if (f.polygons.size() == 1) feature.SetGeometry(multi.getGeometryRef(0));
    else feature.SetGeometry(&multi);
    if (f.height) feature.SetField("height", *f.height);
    if (f.levels) feature.SetField("levels", static_cast<int>(*f.levels));
    REQUIRE(layer->CreateFeature(&feature) == OGRERR_NONE);
  }
}

}  // namespace vgtest
