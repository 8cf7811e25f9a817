// A user's size-distribution CSV; a table that reads is also integrated for
// its moments (the numbers `attenuvis distribution` prints).
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "attenuvis/weather/distribution_file.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  std::istringstream in(fuzz::as_text(data, size));
  fuzz::expect_clean_rejection([&] {
    const auto d = weather::read_distribution_csv(in, "fuzz.csv");
    const auto m = weather::moments(d);
    // The reader promises a positive, finite total; the moments must follow.
    if (!(m.number_per_m3 > 0) || !std::isfinite(m.number_per_m3)) std::abort();
    if (!std::isfinite(m.water_content_kg_m3) || !std::isfinite(m.effective_radius_m)) std::abort();
  });
  return 0;
}
