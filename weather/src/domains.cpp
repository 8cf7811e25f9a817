// Valid ranges of the weather inputs (domains.hpp): messages and help.
#include "attenuvis/weather/domains.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "attenuvis/io/number_text.hpp"

namespace attenuvis::weather {
namespace {

std::string number(double v) { return io::significant(v, 6); }

std::string with_unit(double v, const Domain& d) {
  return d.unit.empty() ? number(v) : number(v) + " " + std::string(d.unit);
}

// The bounds compare with a relative slack of 1e-12: "200nm" and "0.2um" are
// the same bound reached through different roundings.
bool within(double v, double lo, double hi) {
  return v >= lo * (1 - 1e-12) && v <= hi * (1 + 1e-12);
}

}  // namespace

const std::vector<const Domain*>& all_domains() {
  static const std::vector<const Domain*> list = {
      &domain::wavelength,     &domain::visibility,    &domain::sigma,
      &domain::rain_rate,      &domain::snow_rate,     &domain::number_density,
      &domain::water_content,  &domain::index_real,    &domain::index_imag, &domain::shell_volume_fraction,
      &domain::tolerance,      &domain::contrast_threshold, &domain::bulk_density,
      &domain::relative_humidity, &domain::aerosol_mass,
      &domain::drop_radius,    &domain::density_per_radius, &domain::number_per_volume};
  return list;
}

std::string range_text(const Domain& d) {
  std::string out = (d.zero_too ? "0 or [" : "[") + number(d.lo) + ", " + number(d.hi) + "]";
  if (!d.unit.empty()) out += " " + std::string(d.unit);
  return out;
}

std::string domains_help() {
  std::size_t width = 0;
  for (const Domain* d : all_domains()) width = std::max(width, d->quantity.size());
  std::string out;
  for (const Domain* d : all_domains())
    out += "  " + std::string(d->quantity) + std::string(width + 2 - d->quantity.size(), ' ') + range_text(*d) + "\n";
  return out;
}

bool in_domain(const Domain& d, double v) { return (d.zero_too && v == 0) || within(v, d.lo, d.hi); }

double require_in(const Domain& d, double v) {
  if (!in_domain(d, v))
    throw std::invalid_argument(std::string(d.quantity) + " " + with_unit(v, d) + " is outside its valid range " +
                                range_text(d));
  return v;
}

double require_in_si(const Domain& d, double v_si) {
  require_in(d, v_si / d.unit_si);
  return v_si;
}

std::string quote_text(std::string_view text, std::size_t max_chars) {
  if (text.size() <= max_chars) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, max_chars)) + "...' (" + std::to_string(text.size()) + " characters)";
}

double read_in(const Domain& d, std::string_view text) {
  if (text.empty()) throw std::invalid_argument(std::string(d.quantity) + ": a number is missing");
  double v = 0;
  try {
    v = io::parse_double(text, d.quantity);
  } catch (const std::invalid_argument&) {
    // A number beyond the range of a double is a number out of range.
    const std::string s(text);
    char* end = nullptr;
    errno = 0;
    std::strtod(s.c_str(), &end);
    const bool whole = !s.empty() && end == s.c_str() + s.size();
    if (whole && errno == ERANGE)
      throw std::invalid_argument(std::string(d.quantity) + " " + quote_text(text) + " is outside its valid range " +
                                  range_text(d));
    throw std::invalid_argument(std::string(d.quantity) + ": " + quote_text(text) + " is not a number");
  }
  if (!in_domain(d, v))
    throw std::invalid_argument(std::string(d.quantity) + " " + quote_text(text) + " is outside its valid range " +
                                range_text(d));
  return v;
}

}  // namespace attenuvis::weather
