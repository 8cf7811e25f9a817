// Footprint layers (visgraph/gis/footprint_layer.hpp) as GeoJSON, read from
// GDAL's memory file system; footprints that read are extruded
// (footprints.hpp) and handed to Embree.  Only GDAL's GeoJSON driver stays
// registered: the target is this project's reader and extrusion on the
// layers GDAL hands it, not every format GDAL could probe the bytes as.
#include "attenuvis/visgraph/footprints.hpp"
#include "attenuvis/visgraph/gis/footprint_layer.hpp"
#include "attenuvis/visgraph/scene.hpp"
#include "fuzz_input.hpp"

#include <cpl_vsi.h>
#include <gdal_priv.h>

#include <cstring>
#include <vector>

namespace {

const char* const kPath = "/vsimem/fuzz_footprints.geojson";

attenuvis::visgraph::gis::FootprintFields fields() {
  attenuvis::visgraph::gis::FootprintFields f;
  f.height_field = "height";
  f.levels_field = "levels";
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // The reader registers GDAL's drivers on its first call; then all but
  // GeoJSON go.
  static GByte empty[1] = {0};
  VSIFCloseL(VSIFileFromMemBuffer(kPath, empty, 0, FALSE));
  attenuvis::fuzz::expect_clean_rejection([] { attenuvis::visgraph::gis::read_footprints(kPath, fields()); });
  VSIUnlink(kPath);
  // Deregistered drivers are kept here, reachable to the end (a vector that
  // is never destroyed): LeakSanitizer's check at exit would report them.
  static auto* set_aside = new std::vector<GDALDriver*>;
  GDALDriverManager* drivers = GetGDALDriverManager();
  for (int i = drivers->GetDriverCount() - 1; i >= 0; --i) {
    GDALDriver* driver = drivers->GetDriver(i);
    if (std::strcmp(driver->GetDescription(), "GeoJSON") == 0) continue;
    set_aside->push_back(driver);
    drivers->DeregisterDriver(driver);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // GDAL reads the bytes in place (no copy, not freed by GDAL).
  VSIFCloseL(VSIFileFromMemBuffer(kPath, const_cast<GByte*>(data), static_cast<vsi_l_offset>(size), FALSE));
  attenuvis::fuzz::expect_clean_rejection([] {
    const auto layer = attenuvis::visgraph::gis::read_footprints(kPath, fields());
    const attenuvis::visgraph::Mesh mesh =
        attenuvis::visgraph::extrude_footprints(layer.footprints, attenuvis::visgraph::FootprintGround{}, kPath);
    const attenuvis::visgraph::Scene scene(mesh);
    (void)scene;
  });
  VSIUnlink(kPath);
  return 0;
}
