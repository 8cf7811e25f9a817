// GeoPackage output through GDAL (geopackage.hpp).
#include <attenuvis/visgraph/gis/geopackage.hpp>

#include "gdal_support.hpp"

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <unistd.h>

namespace attenuvis::visgraph::gis {

namespace {

std::atomic<unsigned> memory_file_counter{0};

// A file in GDAL's memory file system, removed at scope exit.
class MemoryFile {
 public:
  MemoryFile()
      : path_("/vsimem/attenuvis-" + std::to_string(::getpid()) + "-" + std::to_string(memory_file_counter++) +
              ".gpkg") {}
  ~MemoryFile() { VSIUnlink(path_.c_str()); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  const std::string& path() const { return path_; }
  std::string bytes() const {
    vsi_l_offset length = 0;
    GByte* data = VSIGetMemFileBuffer(path_.c_str(), &length, FALSE);
    return data ? std::string(reinterpret_cast<const char*>(data), static_cast<std::size_t>(length)) : std::string();
  }

 private:
  std::string path_;
};

void fill_layer(OGRLayer& layer, const ScoreTable& table) {
  const std::vector<std::string> columns = score_columns(table);
  std::vector<std::vector<double>> values;
  for (std::size_t c = 3; c < columns.size(); ++c) values.push_back(score_values(table, columns[c]));
  OGRFieldDefn node("node", OFTInteger64);
  if (layer.CreateField(&node) != OGRERR_NONE) throw std::runtime_error("cannot add the field 'node'");
  for (std::size_t c = 3; c < columns.size(); ++c) {
    OGRFieldDefn field(columns[c].c_str(), columns[c] == "degree" ? OFTInteger64 : OFTReal);
    if (layer.CreateField(&field) != OGRERR_NONE) throw std::runtime_error("cannot add the field '" + columns[c] + "'");
  }
  for (std::size_t i = 0; i < table.result->nodes; ++i) {
    OGRFeature feature(layer.GetLayerDefn());
    const Eigen::Vector3d& p = (*table.eyes)[i];
    OGRPoint point(p.x(), p.y(), p.z());
    feature.SetGeometry(&point);
    feature.SetField(0, static_cast<GIntBig>(i));
    for (std::size_t c = 3; c < columns.size(); ++c) {
      const double v = values[c - 3][i];
      const int field = static_cast<int>(c - 2);
      if (!std::isfinite(v)) feature.SetFieldNull(field);
      else if (columns[c] == "degree") feature.SetField(field, static_cast<GIntBig>(v));
      else feature.SetField(field, v);
    }
    if (layer.CreateFeature(&feature) != OGRERR_NONE)
      throw std::runtime_error("cannot write node " + std::to_string(i));
  }
}

}  // namespace

void check_geopackage_crs(const std::string& crs) {
  detail::register_gdal();
  OGRSpatialReference srs;
  if (!crs.empty() && !detail::parse_crs(crs, srs))
    throw std::invalid_argument("the scene's CRS '" + crs + "' is not one GDAL knows: a GeoPackage cannot name it");
}

std::string geopackage_bytes(const ScoreTable& table, const std::string& crs) {
  detail::register_gdal();
  detail::GdalMessages messages;
  OGRSpatialReference srs;
  const bool named = detail::parse_crs(crs, srs);
  if (!crs.empty() && !named) check_geopackage_crs(crs);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!driver) throw std::runtime_error("GDAL has no GeoPackage driver");
  MemoryFile file;
  {
    GDALDatasetUniquePtr dataset(driver->Create(file.path().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset) throw std::runtime_error("cannot create a GeoPackage" + messages.because());
    OGRLayer* layer = dataset->CreateLayer("nodes", named ? &srs : nullptr, wkbPoint25D, nullptr);
    if (!layer) throw std::runtime_error("cannot create the GeoPackage layer" + messages.because());
    // One transaction: a GeoPackage is SQLite, where each insert outside one
    // would be its own transaction (and its own sync).
    if (dataset->StartTransaction() != OGRERR_NONE) throw std::runtime_error("cannot write the GeoPackage" + messages.because());
    try {
      fill_layer(*layer, table);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string("GeoPackage: ") + e.what() + messages.because());
    }
    if (dataset->CommitTransaction() != OGRERR_NONE)
      throw std::runtime_error("cannot write the GeoPackage" + messages.because());
    dataset.reset();  // closes the file (GDAL 3.6 reports no status here: the read-back below checks it)
  }
  std::string bytes = file.bytes();
  if (bytes.size() < 100 || bytes.compare(0, 16, std::string("SQLite format 3\0", 16)) != 0)
    throw std::runtime_error("cannot finish the GeoPackage" + messages.because());
  return bytes;
}

}  // namespace attenuvis::visgraph::gis
