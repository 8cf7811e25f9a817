// refractiveindex.info YAML (index_file.hpp): what the reader accepts gives a
// finite index with n > 0 and k >= 0 across its range, or a clean rejection
// (a formula with no real index at some wavelength is one).
#include <cmath>
#include <cstdlib>

#include "attenuvis/weather/index_file.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  fuzz::expect_clean_rejection([&] {
    const weather::MaterialIndex m = weather::parse_refractiveindex_yaml(fuzz::as_text(data, size), "fuzz.yml");
    const double lo = m.min_wavelength_m(), hi = m.max_wavelength_m();
    if (!(lo > 0) || !(hi >= lo)) std::abort();
    for (double t : {0.0, 0.37, 1.0}) {
      const std::complex<double> v = m.at(lo + t * (hi - lo));
      if (!(v.real() > 0) || !std::isfinite(v.real()) || !(v.imag() >= 0) || !std::isfinite(v.imag())) std::abort();
    }
  });
  return 0;
}
