// Shared weather options of the sigma, table and vg subcommands.
#include "weather_options.hpp"

#include <stdexcept>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/mie/batch.hpp"
#include "attenuvis/weather/domains.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/units.hpp"

namespace attenuvis::cli {
namespace {

namespace w = attenuvis::weather;

// Runs `read`, prefixing any std::invalid_argument with the option's name.
template <class Read>
auto for_option(const char* option, Read read) {
  try {
    return read();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(option) + ": " + e.what());
  }
}

// "hale-querry or segelstein (water), ice (Warren & Brandt 2008)": the
// tables of refractive_index.hpp by substance; a table named after its
// substance names its source instead.
std::string water_table_choices() {
  const auto& tables = w::water_tables();
  std::string out;
  for (std::size_t i = 0, next = 0; i < tables.size(); i = next) {
    std::string names;
    for (next = i; next < tables.size() && tables[next].substance == tables[i].substance; ++next)
      names += (next == i ? "" : " or ") + tables[next].name;
    const bool named_after_substance = next == i + 1 && tables[i].name == tables[i].substance;
    out += (i == 0 ? "" : ", ") + names + " (" + (named_after_substance ? tables[i].source : tables[i].substance) + ")";
  }
  return out;
}

}  // namespace

void add_weather_options(CLI::App* cmd, WeatherOptions& o, WeatherOptionSet which) {
  if (which.wavelength)
    cmd->add_option("--wavelength", o.wavelength,
                    "wavelength with unit, e.g. 550nm or 10.6um; " + w::range_text(w::domain::wavelength))
        ->capture_default_str();
  cmd->add_option("--convention", o.convention,
                  "how P.1817 rain/snow power laws are read: itu (dB/km) or seed (1/km, 4.34x larger)")
      ->capture_default_str();
  cmd->add_option("--threshold", o.threshold,
                  "Koschmieder contrast threshold: 0.02 (3.912) or 0.05 (2.996); " +
                      w::range_text(w::domain::contrast_threshold))
      ->capture_default_str();
  if (which.tolerance)
    cmd->add_option("--tolerance", o.tolerance,
                    "relative tolerance of Mie size integrals; " + w::range_text(w::domain::tolerance))
        ->capture_default_str();
  if (which.tolerance)
    cmd->add_option("--max-evaluations", o.max_evaluations,
                    "Mie evaluations per size integral on the real axis; nearly lossless particles beyond it "
                    "report the error reached (in [1000, 1e9])")
        ->check(CLI::Range(std::size_t{1000}, std::size_t{1000000000}))
        ->capture_default_str();
  cmd->add_option("--water", o.water, "refractive-index table of the drops: " + water_table_choices())
      ->capture_default_str();
}

weather::Settings weather_settings(const WeatherOptions& o) {
  weather::Settings s;
  s.convention = for_option("--convention", [&] { return w::parse_convention(o.convention); });
  s.contrast_threshold = for_option("--threshold", [&] { return w::read_in(w::domain::contrast_threshold, o.threshold); });
  s.rel_tolerance = for_option("--tolerance", [&] { return w::read_in(w::domain::tolerance, o.tolerance); });
  s.max_evaluations = o.max_evaluations;
  if (!w::find_water_table(o.water))
    throw std::invalid_argument("--water: unknown table '" + o.water + "' (" + w::water_table_names() + ")");
  s.water_table = o.water;
  return s;
}

double wavelength_m(const WeatherOptions& o) {
  return for_option("--wavelength", [&] { return w::parse_wavelength(o.wavelength); });
}

std::vector<double> angle_list(const std::string& option, const std::string& text, std::size_t max_count) {
  std::vector<double> angles;
  try {
    angles = mie::batch::parse_angles(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(option + " '" + text + "': " + e.what());
  }
  if (angles.size() > max_count)
    throw std::invalid_argument(option + " '" + text + "' gives " + std::to_string(angles.size()) +
                                " angles, more than " + std::to_string(max_count) + "; give a coarser step");
  return angles;
}

}  // namespace attenuvis::cli
