// Three-column index files (index_file.hpp), under each sign rule: what the
// reader accepts gives n > 0 and k >= 0 at every tabulated wavelength.
#include <cmath>
#include <cstdlib>

#include "attenuvis/weather/index_file.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const std::string text = fuzz::as_text(data, size);
  for (auto sign : {weather::ImaginarySign::detect, weather::ImaginarySign::n_plus_ik,
                    weather::ImaginarySign::n_minus_ik})
    fuzz::expect_clean_rejection([&] {
      const weather::MaterialIndex m = weather::parse_index_columns(text, "fuzz.dat", sign);
      for (double t : {0.0, 0.5, 1.0}) {
        const double w = m.min_wavelength_m() + t * (m.max_wavelength_m() - m.min_wavelength_m());
        const std::complex<double> v = m.at(w);
        if (!(v.real() > 0) || !(v.imag() >= 0) || !std::isfinite(v.real()) || !std::isfinite(v.imag())) std::abort();
      }
    });
  return 0;
}
