// Shared weather options of the sigma, table and vg subcommands.
#include "weather_options.hpp"

#include "attenuvis/weather/units.hpp"
#include "attenuvis/weather/visibility.hpp"

namespace attenuvis::cli {

void add_weather_options(CLI::App* cmd, WeatherOptions& o, WeatherOptionSet which) {
  if (which.wavelength)
    cmd->add_option("--wavelength", o.wavelength, "wavelength, e.g. 550nm or 10.6um")->capture_default_str();
  cmd->add_option("--convention", o.convention,
                  "how P.1817 rain/snow power laws are read: itu (dB/km) or seed (1/km, 4.34x larger)")
      ->capture_default_str();
  cmd->add_option("--threshold", o.threshold, "Koschmieder contrast threshold: 0.02 (3.912) or 0.05 (2.996)")
      ->capture_default_str();
  if (which.tolerance)
    cmd->add_option("--tolerance", o.tolerance, "relative tolerance of Mie size integrals")->capture_default_str();
  cmd->add_option("--water", o.water, "water refractive-index table: hale-querry or segelstein")
      ->capture_default_str();
}

weather::Settings weather_settings(const WeatherOptions& o) {
  weather::Settings s;
  s.convention = weather::parse_convention(o.convention);
  s.contrast_threshold = o.threshold;
  s.rel_tolerance = o.tolerance;
  s.water_table = o.water;
  weather::koschmieder_visibility_m(1.0, o.threshold);  // validates the threshold
  return s;
}

double wavelength_m(const WeatherOptions& o) { return weather::parse_wavelength(o.wavelength); }

}  // namespace attenuvis::cli
