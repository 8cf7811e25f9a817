// Eye-point files given with `vg --nodes`.
#include "attenuvis/visgraph/nodes.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const fuzz::InputFile file(data, size, ".csv");
  fuzz::expect_clean_rejection([&] { visgraph::read_nodes_csv(file.path()); });
  fuzz::expect_clean_rejection([&] { visgraph::parse_point(fuzz::as_text(data, size)); });
  return 0;
}
