// BuildingFootprint layers through GDAL/OGR (footprint_layer.hpp).
#include <attenuvis/visgraph/gis/footprint_layer.hpp>

#include "gdal_support.hpp"

#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/input_file.hpp>
#include <attenuvis/io/number_text.hpp>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace attenuvis::visgraph::gis {

namespace {

// A height in metres from a field's text: a number, optionally followed by
// "m" (OpenStreetMap: "12", "12.5 m"); NaN otherwise.
double height_from_text(std::string text) {
  const auto trim = [](std::string& s) {
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
  };
  trim(text);
  if (!text.empty() && text.back() == 'm') {
    text.pop_back();
    trim(text);
  }
  try {
    return io::parse_double(text, "height");
  } catch (const std::invalid_argument&) {
    return std::nan("");
  }
}

// The field's value as a number, or NaN when unset, null or not a number.
double field_number(const OGRFeature& feature, int field) {
  if (field < 0 || !feature.IsFieldSetAndNotNull(field)) return std::nan("");
  const OGRFieldType type = feature.GetFieldDefnRef(field)->GetType();
  if (type == OFTReal || type == OFTInteger || type == OFTInteger64) return feature.GetFieldAsDouble(field);
  if (type == OFTString) return height_from_text(feature.GetFieldAsString(field));
  return std::nan("");
}

bool usable(double height) { return std::isfinite(height) && height > 0 && height <= kMaxBuildingHeight; }

int field_index(OGRLayer& layer, const std::string& name, const std::string& option, const std::string& path) {
  if (name.empty()) return -1;
  OGRFeatureDefn* definition = layer.GetLayerDefn();
  const int index = definition->GetFieldIndex(name.c_str());
  if (index >= 0) return index;
  std::string names;
  for (int i = 0; i < definition->GetFieldCount(); ++i)
    names += (i ? ", " : "") + std::string(definition->GetFieldDefn(i)->GetNameRef());
  throw std::invalid_argument(path + ": layer '" + layer.GetName() + "' has no field '" + name + "' (" + option +
                              "); its fields: " + (names.empty() ? "none" : names));
}

std::vector<Eigen::Vector3d> ring_points(const OGRLinearRing* ring) {
  std::vector<Eigen::Vector3d> points;
  if (!ring) return points;
  points.reserve(static_cast<std::size_t>(ring->getNumPoints()));
  for (int i = 0; i < ring->getNumPoints(); ++i) points.emplace_back(ring->getX(i), ring->getY(i), ring->getZ(i));
  return points;
}

FootprintPolygon polygon_of(const OGRPolygon& polygon) {
  FootprintPolygon out;
  out.rings.push_back(ring_points(polygon.getExteriorRing()));
  for (int i = 0; i < polygon.getNumInteriorRings(); ++i) out.rings.push_back(ring_points(polygon.getInteriorRing(i)));
  return out;
}

class LayerReader {
 public:
  LayerReader(const std::string& path, const FootprintFields& fields) : path_(path), fields_(fields) {}

  FootprintLayer read() {
    if (!fields_.wanted())
      throw std::invalid_argument(path_ + ": footprints need a height field or a levels field to extrude them");
    if (!(fields_.storey_height > 0 && fields_.storey_height <= 100))
      throw std::invalid_argument("storey height " + io::significant(fields_.storey_height, 6) +
                                  " m is outside (0, 100] m");
    detail::register_gdal();
    detail::GdalMessages messages;
    // Only regular files: GDAL would read a FIFO or a device for ever.
    if (path_.rfind("/vsi", 0) != 0) io::require_readable_input(path_, kMaxSceneFileBytes);
    GDALDatasetUniquePtr dataset(GDALDataset::Open(path_.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!dataset) throw std::runtime_error(path_ + ": not a vector layer GDAL can read" + messages.because());
    if (dataset->GetLayerCount() < 1) throw std::invalid_argument(path_ + ": holds no layer");
    OGRLayer& layer = *dataset->GetLayer(0);
    out_.layers = static_cast<std::size_t>(dataset->GetLayerCount());
    out_.layer = layer.GetName();
    check_crs(layer);
    height_ = field_index(layer, fields_.height_field, "the height field", path_);
    levels_ = field_index(layer, fields_.levels_field, "the levels field", path_);
    read_features(layer);
    if (out_.features == 0) throw std::invalid_argument(path_ + ": layer '" + out_.layer + "' has no features");
    if (out_.footprints.empty())
      throw std::invalid_argument(path_ + ": none of the " + std::to_string(out_.features) +
                                  " features has a usable height (" + out_.first_skipped + ")");
    return std::move(out_);
  }

 private:
  void check_crs(OGRLayer& layer) {
    const OGRSpatialReference* srs = layer.GetSpatialRef();
    out_.crs = detail::crs_text(srs);
    out_.crs_label = detail::crs_label(srs);
    if (!srs) return;
    OGREnvelope extent;
    const bool known = layer.GetExtent(&extent, TRUE) == OGRERR_NONE;
    detail::require_metres(*srs, path_ + " (layer '" + out_.layer + "')", known ? 0.5 * (extent.MinX + extent.MaxX) : 0.0,
                           known ? 0.5 * (extent.MinY + extent.MaxY) : 0.0);
  }

  // The feature's height, or NaN with `why` saying what was wrong.
  double height_of(const OGRFeature& feature, std::string& why) const {
    const double height = field_number(feature, height_);
    if (usable(height)) return height;
    const double levels = field_number(feature, levels_);
    if (std::isfinite(levels) && levels > 0 && usable(levels * fields_.storey_height))
      return levels * fields_.storey_height;
    const auto describe = [&](int field, const std::string& name) {
      if (field < 0) return std::string();
      if (!feature.IsFieldSetAndNotNull(field)) return name + " is empty";
      return name + " is '" + feature.GetFieldAsString(field) + "'";
    };
    why = describe(height_, fields_.height_field);
    const std::string levels_why = describe(levels_, fields_.levels_field);
    why += (why.empty() || levels_why.empty() ? "" : ", ") + levels_why;
    return std::nan("");
  }

  void read_features(OGRLayer& layer) {
    bool all_z = true;
    layer.ResetReading();
    for (auto& feature : layer) {
      ++out_.features;
      const GIntBig fid = feature->GetFID();
      const std::string id = fid == OGRNullFID ? "#" + std::to_string(out_.features) : std::to_string(fid);
      const std::string where = path_ + ": feature " + id;
      const OGRGeometry* geometry = feature->GetGeometryRef();
      if (!geometry) throw std::invalid_argument(where + " has no geometry");
      std::string why;
      const double height = height_of(*feature, why);
      BuildingFootprint footprint;
      footprint.id = id;
      footprint.height = height;
      const OGRwkbGeometryType type = wkbFlatten(geometry->getGeometryType());
      if (type == wkbPolygon) {
        footprint.polygons.push_back(polygon_of(*geometry->toPolygon()));
      } else if (type == wkbMultiPolygon) {
        for (const OGRPolygon* part : *geometry->toMultiPolygon()) footprint.polygons.push_back(polygon_of(*part));
      } else {
        throw std::invalid_argument(where + " is a " + OGRGeometryTypeToName(geometry->getGeometryType()) +
                                    ": footprints must be polygons or multipolygons");
      }
      if (footprint.polygons.empty()) throw std::invalid_argument(where + " is an empty multipolygon");
      if (std::isnan(height)) {
        if (fields_.strict) throw std::invalid_argument(where + " has no usable height (" + why + ")");
        if (out_.skipped++ == 0) out_.first_skipped = "feature " + id + ": " + why;
        continue;
      }
      all_z = all_z && geometry->Is3D();
      extend(footprint);
      out_.footprints.push_back(std::move(footprint));
    }
    out_.vertex_z = all_z && !out_.footprints.empty();
  }

  void extend(const BuildingFootprint& footprint) {
    for (const FootprintPolygon& polygon : footprint.polygons)
      for (const auto& ring : polygon.rings)
        for (const Eigen::Vector3d& p : ring) {
          if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;  // extrusion names it
          if (first_point_) {
            out_.min_x = out_.max_x = p.x();
            out_.min_y = out_.max_y = p.y();
            first_point_ = false;
          }
          out_.min_x = std::min(out_.min_x, p.x());
          out_.max_x = std::max(out_.max_x, p.x());
          out_.min_y = std::min(out_.min_y, p.y());
          out_.max_y = std::max(out_.max_y, p.y());
        }
  }

  const std::string& path_;
  const FootprintFields& fields_;
  FootprintLayer out_;
  int height_ = -1, levels_ = -1;
  bool first_point_ = true;
};

}  // namespace

FootprintLayer read_footprints(const std::string& path, const FootprintFields& fields) {
  return LayerReader(path, fields).read();
}

}  // namespace attenuvis::visgraph::gis
