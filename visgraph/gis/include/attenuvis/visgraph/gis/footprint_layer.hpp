// Building footprints from a GIS vector layer (GeoPackage, Shapefile,
// GeoJSON, any layer GDAL reads) into the typed footprints of
// visgraph/footprints.hpp.
#pragma once

#include <attenuvis/visgraph/footprints.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::visgraph::gis {

// A usable height is a number (or text holding one, optionally followed by
// "m", as OpenStreetMap writes "12 m") above 0 and at most this many metres.
inline constexpr double kMaxBuildingHeight = 1000.0;

struct FootprintFields {
  std::string height_field;  // the building's height in metres
  std::string levels_field;  // its storeys (OpenStreetMap's building:levels), where it has no height
  double storey_height = 3.0;  // m per storey
  bool strict = false;       // a feature without a usable height is an error, not skipped
  bool wanted() const { return !height_field.empty() || !levels_field.empty(); }
};

struct FootprintLayer {
  std::vector<BuildingFootprint> footprints;  // those with a usable height
  std::string layer;                  // the layer's name
  std::size_t layers = 0;             // in the file (the first is read)
  std::string crs;                    // as Mesh::crs holds it ("EPSG:N", or WKT); "" when the layer names none
  std::string crs_label;              // "EPSG:N" or the CRS's name, for messages
  bool vertex_z = false;              // every footprint has z (2.5-D): its bases stand there
  std::size_t features = 0;           // in the layer
  std::size_t skipped = 0;            // without a usable height
  std::string first_skipped;          // the first of those, e.g. "feature 17 (height is empty)"
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;  // extent of the footprints read
};

// Reads the first layer of `path`.  Throws std::invalid_argument or
// std::runtime_error naming the file (and the feature, by its id) for a file
// GDAL cannot open as a vector layer, an empty layer, a field that the layer
// does not have (listing those it has), geometry that is not a polygon or a
// multipolygon, a CRS in degrees or feet (utm.hpp names a zone to use
// instead), a storey height outside (0, 100] m, no field to take heights
// from, and, with `strict`, a feature without a usable height.  Rings are
// checked where they are extruded (footprints.hpp).
FootprintLayer read_footprints(const std::string& path, const FootprintFields& fields);

}  // namespace attenuvis::visgraph::gis
