// Internal to the condition grammar (condition_grammar.cpp, drops_grammar.cpp):
// the ':'-separated fields of one condition with the readers of their numbers,
// and the grammar's shared pieces.
#pragma once

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/domains.hpp"
#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather::detail {

[[noreturn]] inline void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("bad condition " + quote_text(text, 80) + ": " + why + "\n" + condition_grammar());
}

inline std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// One value of a sweep A..B[/STEP][UNIT]: the field it replaces, the number
// (in the sweep's unit) and that unit.
struct SweptValue {
  std::size_t field = 0;
  double value = 0;
  std::string unit;
};

// The ':'-separated fields of one condition (fields[0] is the keyword) and
// the readers of its numbers.  A swept field yields its number directly.
class Fields {
 public:
  Fields(std::string text, std::vector<std::string> fields, std::optional<SweptValue> swept)
      : text_(std::move(text)), fields_(std::move(fields)), swept_(std::move(swept)) {}

  const std::string& text() const { return text_; }
  std::size_t size() const { return fields_.size(); }
  const std::string& operator[](std::size_t i) const { return fields_[i]; }
  [[noreturn]] void fail(const std::string& why) const { bad(text_, why); }
  void require(std::size_t n) const {
    if (fields_.size() < n) fail("missing field after '" + fields_.back() + "'");
  }
  void at_most(std::size_t n, const std::string& why) const {
    if (fields_.size() > n) fail(why);
  }
  bool swept_field_read() const { return !swept_ || swept_read_; }

  // Rate in mm/h within `range` (domains.hpp).
  double rate(std::size_t i, const Domain& range) const {
    try {
      if (const auto v = swept(i)) {
        if (!swept_->unit.empty()) fail("a rate is in mm/h and takes no unit ('" + swept_->unit + "')");
        return require_in(range, *v);
      }
      return read_in(range, fields_[i]);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  // A visibility in metres (units.hpp: parse_distance) within domain::visibility;
  // `from` skips a key ("visibility=") before it.
  double distance(std::size_t i, std::size_t from = 0) const {
    try {
      if (const auto v = swept(i)) {
        if (!(*v > 0)) throw std::invalid_argument("distance must be positive");
        return require_in_si(domain::visibility, *v * distance_unit_m(swept_->unit));
      }
      const std::string text = fields_[i].substr(from);
      const double m = parse_distance(text);
      if (!std::isfinite(m))  // 1e308km
        throw std::invalid_argument("visibility " + quote_text(text) + " is outside its valid range " +
                                    range_text(domain::visibility));
      return require_in_si(domain::visibility, m);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  // sigma in 1/m, from VALUE[/m|/km|dB/km], within domain::sigma.
  double sigma(std::size_t i) const {
    if (const auto v = swept(i)) {
      if (!swept_->unit.empty()) fail("a swept sigma is in 1/m and takes no unit");
      return checked(domain::sigma, *v);
    }
    std::string v = fields_[i];
    SigmaUnit unit = SigmaUnit::per_m;
    for (auto [suffix, u] : {std::pair<const char*, SigmaUnit>{"dB/km", SigmaUnit::dB_per_km},
                             {"/km", SigmaUnit::per_km},
                             {"/m", SigmaUnit::per_m}}) {
      const std::string s = suffix;
      if (v.size() > s.size() && v.compare(v.size() - s.size(), s.size(), s) == 0) {
        unit = u;
        v = v.substr(0, v.size() - s.size());
        break;
      }
    }
    const double x = number(v, "sigma");
    if (x < 0) fail("sigma must be >= 0");
    return checked(domain::sigma, convert_to_per_m(x, unit));
  }
  // The number after a key ("rh=") in field i, or its swept value, within `range`.
  double keyed(std::size_t i, std::size_t key_size, const Domain& range) const {
    if (const auto v = swept(i)) {
      if (!swept_->unit.empty())
        fail("a swept " + fields_[i].substr(0, key_size) + " takes no unit ('" + swept_->unit + "')");
      return checked(range, *v);
    }
    return in(range, fields_[i].substr(key_size));
  }
  // A number read and checked against `range`.
  double in(const Domain& range, const std::string& text) const {
    try {
      return read_in(range, text);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  double checked(const Domain& range, double value) const {
    try {
      return require_in(range, value);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  double number(const std::string& text, const std::string& what) const {
    try {
      return io::parse_double(text, what);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }

 private:
  double number(std::size_t i, const std::string& what) const { return number(fields_[i], what); }
  std::optional<double> swept(std::size_t i) const {
    if (!swept_ || swept_->field != i) return std::nullopt;
    swept_read_ = true;
    return swept_->value;
  }

  std::string text_;
  std::vector<std::string> fields_;
  std::optional<SweptValue> swept_;
  mutable bool swept_read_ = false;
};

// A Mie condition of `drops` with the options (m=, water=, N=, lwc=) in fields from `from` on.
MieCondition with_options(Drops drops, const Fields& f, std::size_t from);

// drops:FAMILY:... (drops_grammar.cpp).
Condition parse_lognormal_drops(const Fields& f);
Condition parse_gamma_drops(const Fields& f);
Condition parse_mgamma_drops(const Fields& f);
Condition parse_exponential_drops(const Fields& f);
Condition parse_powerlaw_drops(const Fields& f);
std::string drops_text(const ParametricDrops& d);

// haze:TYPE:... and aerosol:COMP=N,...:... (aerosol_grammar.cpp).
Condition parse_haze(const Fields& f);
Condition parse_aerosol(const Fields& f);
std::string aerosol_text(const AerosolCondition& c);
// The fields of an aerosol's amounts list may be joined by commas (aerosol:waso=7000,soot=8300):
// true where `text` from `at` starts with a component's "NAME=".
bool starts_with_component(const std::string& text, std::size_t at);
// The help of the aerosol options (growth=, visibility=, mass=), one "grammar  help" pair per option.
std::vector<std::pair<std::string, std::string>> aerosol_option_help();

}  // namespace attenuvis::weather::detail
