// Every kind of name the weather library accepts, in one shape that
// documentation and the Python layer can enumerate.  Each kind keeps its own
// typed table beside the code that uses it; this view reads those tables,
// so a name exists in exactly one place:
//
//   water_tables            water_tables()            refractive_index.hpp  (grammar water=, --water)
//   fog_presets             fog_presets()             size_distribution.hpp (fog:advection, fog:radiation)
//   distribution_presets    distribution_presets()    size_distribution.hpp (the distribution command)
//   rain_power_laws         rain_power_laws()         empirical_models.hpp  (rain:RATE:LAW)
//   snow_types              snow_types()              empirical_models.hpp  (snow:TYPE:RATE)
//   visibility_fog_models   visibility_fog_models()   empirical_models.hpp  (fog:MODEL:DIST)
//   table_quantities        table_quantities()        table_quantity.hpp    (table --quantities)
//   aerosol_components      aerosol_components()      aerosol.hpp           (aerosol:COMP=N; numbers from data/opac)
//   aerosol_mixtures        aerosol_mixtures()        aerosol.hpp           (haze:TYPE)
//   humidity_rules          humidity_rules()          aerosol.hpp           (:growth=RULE)
#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

namespace attenuvis::weather {

// One name of a registry, with its units, help and source.
struct RegistryEntry {
  std::string name;      // as the grammar, the command line and Python spell it
  std::string units;     // of what it names ("dB/km", "1/m"); "" where none is meaningful
  std::string help;      // one line
  std::string citation;  // the published source; "" where there is none
  // What else the kind knows, by key: a table's "aliases" and "file", a
  // power law's "k", "alpha" and whether it is the "default", a quantity's
  // "python_name" and "long_name", a component's dry "mode_radius_um", a
  // mixture's number density per component name.
  using Detail = std::variant<bool, double, std::string, std::vector<std::string>>;
  std::map<std::string, Detail> details;
};

// "water_tables", "fog_presets", ...: the kinds above, in that order.
const std::vector<std::string>& registry_kinds();
// The entries of one kind, in its table's order; throws std::invalid_argument
// naming the kinds for any other text.
std::vector<RegistryEntry> registry(const std::string& kind);

}  // namespace attenuvis::weather
