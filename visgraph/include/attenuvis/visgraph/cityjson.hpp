// CityJSON 1.0, 1.1 and 2.0 (and CityJSONSeq, one feature per line) into a
// Mesh: one group per city object (its id), one class per triangle (its
// semantic surface type, or its city object's type where the geometry has no
// semantics), the CRS from metadata.referenceSystem.
//
// Geometry types: MultiSurface, CompositeSurface, Solid, MultiSolid,
// CompositeSolid and GeometryInstance (templates placed by their reference
// point and 4x4 transformation).  Every surface is triangulated as a polygon
// with holes (detail/polygon.hpp); surfaces of zero area are counted and skipped.
// Coordinates: vertices x scale + translate (the file's `transform`), metres.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <cstddef>
#include <string>

namespace attenuvis::visgraph {

// How a CityJSON file is read.
struct CityJsonOptions {
  // Level of detail to read, as the file writes it ("2", "2.2"); empty:
  // each city object's highest LoD.
  std::string lod;
};

// What a CityJSON file held and what reading it skipped.
struct CityJsonReport {
  std::string version;              // "1.0", "1.1", "2.0"
  std::size_t city_objects = 0;     // in the file
  std::size_t objects_read = 0;     // with a geometry at the chosen LoD
  std::size_t surfaces = 0;         // polygons read
  std::size_t degenerate_surfaces = 0;  // zero area: skipped
  std::size_t invalid_surfaces = 0;     // self-intersecting: partly triangulated
  std::size_t triangles = 0;
};

// True if the text (a file's first bytes will do) is CityJSON or CityJSONSeq.
bool looks_like_cityjson(const std::string& head);

// Throws std::runtime_error naming the file and the place (byte offset, line
// and column of a syntax error; the city object and geometry of a bad
// boundary or vertex index) for malformed input, and for a file or LoD that
// yields no triangle.
Mesh load_cityjson(const std::string& path, const CityJsonOptions& options = {}, CityJsonReport* report = nullptr);

// "EPSG:28992" for the usual spellings of an EPSG CRS
// ("urn:ogc:def:crs:EPSG::28992", "https://www.opengis.net/def/crs/EPSG/0/28992");
// otherwise the text unchanged.
std::string short_crs_name(const std::string& crs);

}  // namespace attenuvis::visgraph
