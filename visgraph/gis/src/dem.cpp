// DEM windows through GDAL (dem.hpp).
#include <attenuvis/visgraph/gis/dem.hpp>

#include "gdal_support.hpp"

#include <attenuvis/visgraph/cityjson.hpp>
#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/input_file.hpp>
#include <attenuvis/io/number_text.hpp>

#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace attenuvis::visgraph::gis {

namespace {

std::string extent_text(double x0, double y0, double x1, double y1) {
  return "x " + io::significant(x0, 10) + " to " + io::significant(x1, 10) + ", y " + io::significant(y0, 10) +
         " to " + io::significant(y1, 10);
}

// Index range [first, last] of the cells (of `count`, centres at
// origin + (i + 1/2) step) whose centres lie within [lo, hi], grown by one
// cell so that the triangles reach lo and hi; clamped to the raster.
void cell_range(double origin, double step, long count, double lo, double hi, long& first, long& last) {
  double a = (lo - origin) / step - 0.5, b = (hi - origin) / step - 0.5;
  if (a > b) std::swap(a, b);
  first = std::max(0L, static_cast<long>(std::floor(a)) - 1);
  last = std::min(count - 1, static_cast<long>(std::ceil(b)) + 1);
}

}  // namespace

Dem read_dem(const std::string& path, const DemRequest& request) {
  detail::register_gdal();
  detail::GdalMessages messages;
  if (path.rfind("/vsi", 0) != 0) io::require_readable_input(path, kMaxSceneFileBytes);
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) throw std::runtime_error(path + ": not a raster GDAL can read" + messages.because());
  if (dataset->GetRasterCount() < 1) throw std::invalid_argument(path + ": has no raster band");
  double gt[6];
  if (dataset->GetGeoTransform(gt) != CE_None)
    throw std::invalid_argument(path + ": has no georeferencing (no geotransform): its cells have no position");
  if (gt[2] != 0 || gt[4] != 0)
    throw std::invalid_argument(path + ": is rotated or sheared; warp it north-up first (gdalwarp)");
  if (!(gt[1] > 0) || gt[5] == 0) throw std::invalid_argument(path + ": has a cell size of zero or a negative width");
  const long width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  Dem dem;
  const OGRSpatialReference* srs = dataset->GetSpatialRef();
  dem.crs = detail::crs_text(srs);
  dem.crs_label = detail::crs_label(srs);
  if (srs && !request.model_crs.empty() && !detail::same_horizontal_crs(request.model_crs, *srs))
    throw std::invalid_argument(path + " is in " + dem.crs_label + " but the model in " +
                                short_crs_name(request.model_crs) +
                                ": give a DEM in the model's CRS (gdalwarp -t_srs " + short_crs_name(request.model_crs) + ")");
  if (srs) detail::require_metres(*srs, path, gt[0] + 0.5 * width * gt[1], gt[3] + 0.5 * height * gt[5]);
  // The cell centres' extent must hold the model's.
  const double cx0 = gt[0] + 0.5 * gt[1], cx1 = gt[0] + (static_cast<double>(width) - 0.5) * gt[1];
  const double cy_a = gt[3] + 0.5 * gt[5], cy_b = gt[3] + (static_cast<double>(height) - 0.5) * gt[5];
  const double cy0 = std::min(cy_a, cy_b), cy1 = std::max(cy_a, cy_b);
  if (width < 2 || height < 2 || request.min_x < cx0 || request.max_x > cx1 || request.min_y < cy0 ||
      request.max_y > cy1)
    throw std::invalid_argument(path + " does not cover the model: its cell centres span " +
                                extent_text(cx0, cy0, cx1, cy1) + ", the model " +
                                extent_text(request.min_x, request.min_y, request.max_x, request.max_y));
  long c0 = 0, c1 = 0, r0 = 0, r1 = 0;
  cell_range(gt[0], gt[1], width, request.min_x - request.margin, request.max_x + request.margin, c0, c1);
  cell_range(gt[3], gt[5], height, request.min_y - request.margin, request.max_y + request.margin, r0, r1);
  const long cols = c1 - c0 + 1, rows = r1 - r0 + 1;
  const double cells = static_cast<double>(cols) * static_cast<double>(rows);
  if (request.max_cells > 0 && cells > request.max_cells)
    throw std::invalid_argument(path + ": the model's extent covers " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " = " + io::significant(cells, 3) + " cells of " +
                                io::significant(gt[1], 4) + " m, more than the " + io::significant(request.max_cells, 3) +
                                " a terrain may have (~150 bytes each): resample it coarser, e.g. gdalwarp -tr 2 2");
  GDALRasterBand* band = dataset->GetRasterBand(1);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const double scale = band->GetScale(), offset = band->GetOffset();
  HeightGrid& g = dem.grid;
  g.cols = static_cast<std::size_t>(cols);
  g.rows = static_cast<std::size_t>(rows);
  g.dx = gt[1];
  g.dy = gt[5];
  g.x0 = gt[0] + (static_cast<double>(c0) + 0.5) * gt[1];
  g.y0 = gt[3] + (static_cast<double>(r0) + 0.5) * gt[5];
  g.col0 = c0;
  g.row0 = r0;
  g.z.assign(g.cols * g.rows, 0.0);
  if (band->RasterIO(GF_Read, static_cast<int>(c0), static_cast<int>(r0), static_cast<int>(cols), static_cast<int>(rows),
                     g.z.data(), static_cast<int>(cols), static_cast<int>(rows), GDT_Float64, 0, 0, nullptr) != CE_None)
    throw std::runtime_error(path + ": cannot read its cells" + messages.because());
  for (double& z : g.z) {
    if ((has_nodata && (z == nodata || (std::isnan(nodata) && std::isnan(z)))) || !std::isfinite(z)) {
      z = std::nan("");
      continue;
    }
    z = z * scale + offset;
    check_coordinate(z, path + ": cell height");
  }
  for (long r = 0; r < rows; r += std::max(1L, rows - 1))
    for (long c = 0; c < cols; c += std::max(1L, cols - 1)) {
      const Eigen::Vector2d p = g.centre(static_cast<std::size_t>(c), static_cast<std::size_t>(r));
      check_coordinate(p.x(), path + ": cell centre");
      check_coordinate(p.y(), path + ": cell centre");
    }
  dem.description = path + " (" + (dem.crs_label.empty() ? "no CRS" : dem.crs_label) + ", " +
                    io::significant(gt[1], 4) + " x " + io::significant(std::abs(gt[5]), 4) + " m cells; a window of " +
                    std::to_string(cols) + " x " + std::to_string(rows) + " of its " + std::to_string(width) + " x " +
                    std::to_string(height) + ")";
  return dem;
}

}  // namespace attenuvis::visgraph::gis
