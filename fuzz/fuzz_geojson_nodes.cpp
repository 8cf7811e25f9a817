// GeoJSON point files given with `vg --nodes` / `--targets`.
#include "attenuvis/visgraph/geojson.hpp"
#include "attenuvis/visgraph/nodes.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const fuzz::InputFile file(data, size, ".geojson");
  fuzz::expect_clean_rejection([&] { visgraph::read_geojson_points(file.path()); });
  fuzz::expect_clean_rejection([&] { visgraph::read_nodes(file.path()); });
  return 0;
}
