// Per-node scores as a GeoPackage point layer, the format QGIS uses natively,
// written through GDAL.
#pragma once

#include <attenuvis/visgraph/outputs.hpp>

#include <string>

namespace attenuvis::visgraph::gis {

// Throws std::invalid_argument when `crs` (as Mesh::crs holds it) is neither
// empty nor a CRS GDAL knows, so that a run can refuse before its pass
// rather than after it.
void check_geopackage_crs(const std::string& crs);

// The bytes of a GeoPackage with one layer "nodes": a 3-D point per node (x,
// y, z in the scene's frame), with fields "node" (0-based, as the CSV rows),
// "degree" (an integer, when exact) and every other score column of
// score_columns() as a real number (NaN as NULL), in the CRS `crs` (empty:
// an undefined Cartesian CRS).  Built in GDAL's memory file system, so that
// the caller can stage it like any other output (io/staged_file.hpp).
std::string geopackage_bytes(const ScoreTable& table, const std::string& crs);

}  // namespace attenuvis::visgraph::gis
