// The `attenuvis mie` batch line, refractive index and angle grammars; a line
// that parses is also evaluated, with its amplitudes at three angles, where x
// is small enough for the fuzzer to keep its pace.
#include <cmath>
#include <cstdlib>

#include "attenuvis/mie/batch.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_clean_rejection([&] {
    const auto problem = mie::batch::parse_line(text);
    if (!problem || problem->x > 1e3) return;
    mie::Extras extras;
    extras.angles_deg = {0.0, 90.0, 180.0};
    const auto s = mie::scatter(problem->x, problem->m, extras);
    if (!std::isfinite(s.q.qext) || !std::isfinite(s.q.qsca) || !std::isfinite(s.q.qback)) std::abort();
  });
  fuzz::expect_clean_rejection([&] { mie::batch::parse_refractive_index(text); });
  fuzz::expect_clean_rejection([&] { mie::batch::parse_angles(text); });
  return 0;
}
