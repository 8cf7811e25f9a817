// OPAC's size_distr.cfg (opac_data.hpp): every row the reader accepts obeys
// what it promises (component 1..10, 0 < Rmin < Rmod < Rmax, rho > 0, sigma > 1).
#include <cstdlib>

#include "attenuvis/weather/opac_data.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  fuzz::expect_clean_rejection([&] {
    for (const auto& r : weather::parse_opac_size_table(fuzz::as_text(data, size), "fuzz.cfg"))
      if (r.component < 1 || r.component > 10 || !(r.r_min_um > 0 && r.r_min_um < r.r_mod_um &&
                                                    r.r_mod_um < r.r_max_um) ||
          !(r.density_g_cm3 > 0) || !(r.sigma_g > 1))
        std::abort();
  });
  return 0;
}
