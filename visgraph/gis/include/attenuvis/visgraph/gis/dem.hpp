// A digital elevation model (a GeoTIFF, or any raster GDAL reads) as the
// terrain grid of visgraph/terrain.hpp, read only around the model.
#pragma once

#include <attenuvis/visgraph/terrain.hpp>

#include <string>

namespace attenuvis::visgraph::gis {

// Cells a DEM window may have by default: each becomes a vertex and two
// triangles, ~150 bytes with Embree's BVH, so 4e6 cells (2000 x 2000, a
// square kilometre at 0.5 m) take ~0.6 GB.
inline constexpr double kDefaultMaxTerrainCells = 4e6;

struct DemRequest {
  // The model's horizontal extent, m: the DEM must cover it.
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  double margin = 1.0;  // m read beyond it on every side (where the raster has them)
  double max_cells = kDefaultMaxTerrainCells;  // 0 = no limit
  // The model's CRS as Mesh::crs holds it ("" when it names none): a DEM in
  // another horizontal CRS is refused (vertical datums are not compared).
  std::string model_crs;
};

struct Dem {
  HeightGrid grid;        // the window
  std::string crs;        // as Mesh::crs holds it; "" when the raster names none
  std::string crs_label;  // "EPSG:N" or its name, for messages
  std::string description;  // "dem.tif (EPSG:32632, 1 x 1 m cells; a window of 120 x 80 of its 2000 x 2000)"
};

// Reads band 1 of `path` (its scale and offset applied, its nodata value as
// NaN) in the window of cells whose centres reach the request's extent plus
// its margin.  Throws std::invalid_argument or std::runtime_error naming the
// file for a file GDAL cannot open as a raster, a CRS other than the model's
// (naming both; checked first), a raster without
// georeferencing or rotated/sheared, one whose cell centres do not cover the
// model's extent (naming both extents), a CRS in degrees or feet, and a
// window of more than max_cells cells (with the size and what to do).
Dem read_dem(const std::string& path, const DemRequest& request);

}  // namespace attenuvis::visgraph::gis
