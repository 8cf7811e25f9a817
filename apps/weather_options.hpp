// The weather options shared by every subcommand that computes sigma (sigma,
// table, vg): each option means the same in all of them, and all build their
// weather::Settings here.  Numbers are taken as text and read against their
// domains (weather/domains.hpp), so an error names the option, the value and
// the valid range in the same words everywhere.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "attenuvis/weather/settings.hpp"

namespace attenuvis::cli {

struct WeatherOptions {
  std::string wavelength = "550nm";
  std::string convention = "itu";
  std::string threshold = "0.02";
  std::string tolerance = "1e-9";
  std::size_t max_evaluations = 1000000;
  std::string water = "hale-querry";
};

// Which of the shared options a subcommand takes.
struct WeatherOptionSet {
  bool wavelength = true;  // --wavelength (table has --wavelengths instead)
  bool tolerance = true;   // --tolerance, the Mie tolerance (vg keeps the name for its deprecated prune alias)
};

// Adds --convention, --threshold, --water and, per `which`, --wavelength and --tolerance.
void add_weather_options(CLI::App* cmd, WeatherOptions& o, WeatherOptionSet which = {});

// Settings from the options; throws std::invalid_argument "--OPTION: ..." naming a bad value.
weather::Settings weather_settings(const WeatherOptions& o);
// The --wavelength value in metres.
double wavelength_m(const WeatherOptions& o);

// Scattering angles (degrees) of an option such as --angles: the grammar of
// mie::batch::parse_angles (START:STOP:STEP, STOP included when on the grid,
// or A,B,...; each in [0, 180]; a grid's angles rounded to 12 significant
// digits, so 0:1:0.1 gives 0.3).  Throws std::invalid_argument
// "OPTION 'TEXT': ..." for a bad grid or more than max_count angles.
std::vector<double> angle_list(const std::string& option, const std::string& text, std::size_t max_count);

}  // namespace attenuvis::cli
