// The valid range of every number a user gives the weather module, stated
// once.  The condition grammar's help (condition_grammar()), the command-line
// --help texts, every out-of-range message and the README's table of ranges
// all come from this list; a test checks the README against it.
//
// A range keeps each computation inside what its model and its integrator
// support: wavelengths where the water tables have data (Hale & Querry 1973:
// 0.2-200 um), rates and visibilities that real weather reaches, rescalings
// and distribution values whose moments stay far from double overflow and
// underflow, tolerances the quadratures can meet within their budgets.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace attenuvis::weather {

// The valid range of one input quantity, in the unit it is written in.
struct Domain {
  std::string_view quantity;  // "rain rate"
  std::string_view unit;      // "mm/h"; "" for a pure number
  double unit_si = 1;         // one `unit` in SI (values held in SI are checked through it)
  double lo = 0, hi = 0;      // valid: [lo, hi] in `unit`...
  bool zero_too = false;      // ...and 0 as well
};

namespace domain {
// The valid range of every input quantity (the guide's table of valid ranges).
inline constexpr Domain wavelength{"wavelength", "um", 1e-6, 0.2, 200};
inline constexpr Domain visibility{"visibility", "m", 1, 1, 1e6};
inline constexpr Domain sigma{"sigma", "1/m", 1, 1e-12, 1e3, true};
inline constexpr Domain rain_rate{"rain rate", "mm/h", 1, 0.01, 500};
inline constexpr Domain snow_rate{"snow rate", "mm/h", 1, 0.01, 100};
inline constexpr Domain number_density{"number density N", "cm^-3", 1e6, 1e-6, 1e6};
inline constexpr Domain water_content{"liquid water content lwc", "g/m^3", 1e-3, 1e-9, 50};
inline constexpr Domain index_real{"refractive index real part n", "", 1, 0.01, 10};
inline constexpr Domain index_imag{"refractive index imaginary part k", "", 1, 0, 10};
inline constexpr Domain shell_volume_fraction{"shell volume fraction", "", 1, 0, 0.999};
inline constexpr Domain tolerance{"Mie tolerance", "", 1, 1e-13, 1e-2};
inline constexpr Domain contrast_threshold{"contrast threshold", "", 1, 1e-6, 0.5};
inline constexpr Domain bulk_density{"bulk density", "kg/m^3", 1, 1, 2e4};
// Aerosols (aerosol.hpp): OPAC tabulates up to 99 %, where sea salt has grown
// fivefold; beyond it kappa-Koehler growth diverges (a_w -> 1).
inline constexpr Domain relative_humidity{"relative humidity RH", "%", 1, 0, 99};
inline constexpr Domain aerosol_mass{"aerosol dry mass concentration", "ug/m^3", 1e-9, 1e-6, 1e5};
// Size-distribution files (distribution_file.hpp), after conversion to SI.
inline constexpr Domain drop_radius{"radius", "m", 1, 1e-9, 0.1};
inline constexpr Domain density_per_radius{"dN/dr", "m^-4", 1, 1e-20, 1e30, true};
inline constexpr Domain number_per_volume{"dN/dln r or bin count", "m^-3", 1, 1e-20, 1e24, true};
}  // namespace domain

// Every domain above, in the order the help lists them.
const std::vector<const Domain*>& all_domains();

// "[0.01, 500] mm/h", "0 or [1e-12, 1000] 1/m".
std::string range_text(const Domain& d);
// "  rain rate  [0.01, 500] mm/h" lines for every domain (help texts).
std::string domains_help();

// True when the value lies in the domain.
bool in_domain(const Domain& d, double value_in_unit);

// Return the value, or throw std::invalid_argument
//   "rain rate 1000 mm/h is outside its valid range [0.01, 500] mm/h"
// (the caller prefixes where the value came from).
double require_in(const Domain& d, double value_in_unit);
double require_in_si(const Domain& d, double value_si);  // value in SI, message in `unit`

// Reads `text` as a number in the domain's unit and checks it.  A number no
// double holds (1e400, 1e-400) is reported as out of range, not as text that
// is no number; the text is quoted shortened to 40 characters.
double read_in(const Domain& d, std::string_view text);

// `text` quoted for a message, cut to `max_chars` with "..." (a 300-digit
// number should not fill the screen).
std::string quote_text(std::string_view text, std::size_t max_chars = 40);

}  // namespace attenuvis::weather
