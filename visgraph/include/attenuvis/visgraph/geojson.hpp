// GeoJSON in and out: per-node scores as a point layer a GIS opens directly
// (QGIS, GDAL), and eye positions read from GeoJSON points.
//
// CRS.  RFC 7946 fixes GeoJSON coordinates to WGS84 unless the parties agree
// otherwise; city models are in projected CRSs (metres), and reprojecting
// would change the distances the scores are made of.  The file therefore
// keeps the scene's coordinates and names their CRS with the `crs` member of
// the 2008 GeoJSON specification ({"type": "name", "properties": {"name":
// "urn:ogc:def:crs:EPSG::28992"}}), which QGIS and GDAL read.
#pragma once

#include <attenuvis/visgraph/outputs.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace attenuvis::visgraph {

// FeatureCollection of 3D points, one per node, each with properties
// "node" (0-based index, as the CSV rows) and every score column of
// score_columns() (NaN as null).  `crs` as the scene names it (empty: no crs
// member, coordinates in an unnamed local frame).  Written atomically.
void write_geojson(const std::string& path, const ScoreTable& table, const std::string& crs);
// The same document as text (for a caller that stages several outputs).
std::string geojson_text(const ScoreTable& table, const std::string& crs);

// The crs name to put in the file: "urn:ogc:def:crs:EPSG::N" for any EPSG
// spelling; other names unchanged.
std::string geojson_crs_name(const std::string& crs);

// The points of a GeoJSON node file, with the file's CRS.
struct GeoJsonPoints {
  std::vector<Eigen::Vector3d> points;
  std::string crs;  // the file's crs member, empty if none
};

// Points of a GeoJSON file: a FeatureCollection of Point or MultiPoint
// features, a single Feature, or a bare geometry.  Every point needs x, y
// and z (the eye position, metres).  Throws naming the file and the feature
// for anything else (a polygon, a point without z, a syntax error with its
// line and column).
GeoJsonPoints read_geojson_points(const std::string& path);

}  // namespace attenuvis::visgraph
