// The `attenuvis mie` batch line (homogeneous and layered), refractive index,
// angle and --layers grammars; a line that parses is also evaluated, with its
// amplitudes at three angles, where x is small enough for the fuzzer to keep
// its pace (a layered one through layered_spheres(), which reports a particle
// outside the domain instead of throwing).
#include <cmath>
#include <cstdlib>

#include "attenuvis/mie/batch.hpp"
#include "attenuvis/mie/layered.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace attenuvis;
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_clean_rejection([&] {
    const auto problem = mie::batch::parse_line(text);
    if (!problem || problem->x > 1e3) return;
    if (!problem->layer_x.empty()) {
      if (problem->layer_x.size() > 8) return;
      for (const auto& m : problem->layer_m)
        if (std::abs(m) * problem->x > 1e4) return;  // the recurrences' start: ~|m x| steps
      const std::size_t offsets[2] = {0, problem->layer_x.size()};
      mie::Efficiencies<double> q;
      mie::SpheresOptions one_thread;
      one_thread.threads = 1;
      const auto errors = mie::layered_spheres(offsets, problem->layer_x.data(), problem->layer_m.data(), 1, &q,
                                               one_thread);
      if (errors.empty() && (!std::isfinite(q.qext) || !std::isfinite(q.qsca) || !std::isfinite(q.qback)))
        std::abort();
      return;
    }
    mie::Extras extras;
    extras.angles_deg = {0.0, 90.0, 180.0};
    const auto s = mie::scatter(problem->x, problem->m, extras);
    if (!std::isfinite(s.q.qext) || !std::isfinite(s.q.qsca) || !std::isfinite(s.q.qback)) std::abort();
  });
  fuzz::expect_clean_rejection([&] { mie::batch::parse_refractive_index(text); });
  fuzz::expect_clean_rejection([&] { mie::batch::parse_angles(text); });
  fuzz::expect_clean_rejection([&] { mie::batch::parse_layers(text, "--layers"); });
  return 0;
}
