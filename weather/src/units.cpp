// Unit parsing and conversion for sigma, wavelengths and distances.
#include "attenuvis/weather/units.hpp"

#include <cctype>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/domains.hpp"

namespace attenuvis::weather {

std::string to_string(Convention c) { return c == Convention::itu ? "itu" : "seed"; }

Convention parse_convention(const std::string& text) {
  if (text == "itu") return Convention::itu;
  if (text == "seed") return Convention::seed;
  throw std::invalid_argument("unknown convention '" + text +
                              "' (expected 'itu': P.1817 power laws in dB/km, or 'seed': read as 1/km)");
}

std::string to_string(SigmaUnit u) {
  switch (u) {
    case SigmaUnit::per_m: return "1/m";
    case SigmaUnit::per_km: return "1/km";
    case SigmaUnit::dB_per_km: return "dB/km";
  }
  return "?";
}

SigmaUnit parse_sigma_unit(const std::string& text) {
  if (text == "m" || text == "1/m" || text == "m^-1" || text == "/m") return SigmaUnit::per_m;
  if (text == "km" || text == "1/km" || text == "km^-1" || text == "/km") return SigmaUnit::per_km;
  if (text == "dB/km" || text == "db/km") return SigmaUnit::dB_per_km;
  throw std::invalid_argument("unknown sigma unit '" + text + "' (expected m, km or dB/km)");
}

double convert_from_per_m(double s, SigmaUnit to) {
  switch (to) {
    case SigmaUnit::per_m: return s;
    case SigmaUnit::per_km: return per_m_to_per_km(s);
    case SigmaUnit::dB_per_km: return per_m_to_dB_per_km(s);
  }
  return s;
}

double convert_to_per_m(double v, SigmaUnit from) {
  switch (from) {
    case SigmaUnit::per_m: return v;
    case SigmaUnit::per_km: return per_km_to_per_m(v);
    case SigmaUnit::dB_per_km: return dB_per_km_to_per_m(v);
  }
  return v;
}

namespace {
// The one list of distance units: parse_distance, its messages and the
// condition grammar's help all read it.
struct DistanceUnit {
  const char* name;
  double metres;
};
constexpr DistanceUnit kDistanceUnits[] = {{"m", 1.0}, {"km", 1e3}, {"mi", 1609.344}};

// Splits "12.5km" into the number and the unit suffix (spaces allowed between).
std::pair<std::string, std::string> split_number_unit(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' ||
                             text[i] == '-' || text[i] == '+' ||
                             ((text[i] == 'e' || text[i] == 'E') && i > 0 && i + 1 < text.size() &&
                              (std::isdigit(static_cast<unsigned char>(text[i + 1])) || text[i + 1] == '-' ||
                               text[i + 1] == '+'))))
    ++i;
  std::string unit = text.substr(i);
  while (!unit.empty() && unit.front() == ' ') unit.erase(unit.begin());
  return {text.substr(0, i), unit};
}
}  // namespace

double parse_length(const std::string& text, const std::string& what) {
  auto [num, unit] = split_number_unit(text);
  if (unit.empty())
    throw std::invalid_argument(what + " " + quote_text(text) + " needs a unit (nm, um, mm or m), e.g. 550nm");
  double scale = 0;
  if (unit == "nm") scale = 1e-9;
  else if (unit == "um" || unit == "µm" || unit == "micron") scale = 1e-6;
  else if (unit == "mm") scale = 1e-3;
  else if (unit == "m") scale = 1;
  else throw std::invalid_argument(what + " " + quote_text(text) + ": unknown unit " + quote_text(unit) + " (nm, um, mm or m)");
  // Read in the unit given, so that 1e300m is reported as out of range, not as overflow.
  const Domain in_unit{what, unit, scale, 0, std::numeric_limits<double>::max()};
  const double v = read_in(in_unit, num);
  if (!(v > 0)) throw std::invalid_argument(what + " " + quote_text(text) + " must be positive");
  return v * scale;
}

double parse_wavelength(const std::string& text) {
  const double m = parse_length(text, "wavelength");
  if (!in_domain(domain::wavelength, m / domain::wavelength.unit_si))
    throw std::invalid_argument("wavelength " + quote_text(text) + " is outside its valid range " +
                                range_text(domain::wavelength) + " (where the water tables have data)");
  return m;
}

const std::string& distance_units() {
  static const std::string list = [] {
    std::string out;
    const std::size_t n = std::size(kDistanceUnits);
    for (std::size_t i = 0; i < n; ++i) out += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + kDistanceUnits[i].name;
    return out;
  }();
  return list;
}

double distance_unit_m(const std::string& unit) {
  if (unit.empty()) return 1.0;
  for (const auto& u : kDistanceUnits)
    if (unit == u.name) return u.metres;
  throw std::invalid_argument("unknown distance unit '" + unit + "' (" + distance_units() + ")");
}

double parse_distance(const std::string& text) {
  auto [num, unit] = split_number_unit(text);
  double v = io::parse_double(num, "distance");
  double scale = 0;
  try {
    scale = distance_unit_m(unit);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("distance '" + text + "': unknown unit '" + unit + "' (" + distance_units() + ")");
  }
  if (!(v > 0)) throw std::invalid_argument("distance '" + text + "' must be positive");
  return v * scale;
}

}  // namespace attenuvis::weather
