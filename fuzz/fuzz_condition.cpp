// The condition grammar: parse_condition and expand_conditions on any text,
// and sigma() of what they accept for the kinds that need no Mie integral
// (power laws, visibilities, a given sigma), at wavelengths across the
// domain, and the text of an aerosol (haze:, aerosol:) written back.  The
// grammar promises that whatever it accepts lies in the domains (domains.hpp),
// where sigma is finite and >= 0.
#include <cmath>
#include <cstdlib>
#include <string>
#include <variant>

#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace attenuvis;

void check_sigma(const weather::Condition& c) {
  // An aerosol, written back, must parse to the same text (its integrals are too slow for a fuzzer).
  if (std::holds_alternative<weather::AerosolCondition>(c)) {
    const std::string text = weather::to_text(c);
    if (weather::to_text(weather::parse_condition(text)) != text) std::abort();
    return;
  }
  if (weather::needs_mie(c)) return;  // seconds per integral: too slow for a fuzzer
  for (const double wavelength : {200e-9, 550e-9, 10.6e-6, 200e-6}) {
    for (const auto convention : {weather::Convention::itu, weather::Convention::seed}) {
      weather::Settings s;
      s.convention = convention;
      const weather::Sigma r = weather::sigma(c, wavelength, s);
      if (!std::isfinite(r.per_m) || !(r.per_m >= 0) || !std::isfinite(r.error_per_m)) std::abort();
    }
  }
  // What the grammar accepted, written back, must parse to the same kind.
  if (weather::parse_condition(weather::to_text(c)).index() != c.index()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_clean_rejection([&] { check_sigma(weather::parse_condition(text)); });
  fuzz::expect_clean_rejection([&] {
    for (const auto& c : weather::expand_conditions(text)) check_sigma(c.condition);
  });
  return 0;
}
