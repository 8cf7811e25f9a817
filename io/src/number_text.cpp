#include "attenuvis/io/number_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace attenuvis::io {

double parse_double(std::string_view text, std::string_view what) {
  // The message is built only on failure: tables of a million numbers pass through here.
  const auto quoted = [&] { return std::string(what) + ": '" + std::string(text) + "'"; };
  if (text.empty()) throw std::invalid_argument(std::string(what) + ": a number is missing");
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (*begin == '+') ++begin;  // from_chars takes no leading '+'
  double value = 0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range)
    throw std::invalid_argument(quoted() + " is out of the range of a double");
  if (ec != std::errc() || ptr != end) throw std::invalid_argument(quoted() + " is not a number");
  if (!std::isfinite(value)) throw std::invalid_argument(quoted() + " is not finite");
  return value;
}

std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string significant(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

double half_unit_in_last_digit(std::string_view literal) {
  std::string_view mantissa = literal;
  int exponent = 0;
  const auto e = literal.find_first_of("eE");
  if (e != std::string_view::npos) {
    mantissa = literal.substr(0, e);
    exponent = std::stoi(std::string(literal.substr(e + 1)));
  }
  const auto dot = mantissa.find('.');
  const int decimals = dot == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return 0.5 * std::pow(10.0, exponent - decimals);
}

IndexText split_index_text(std::string_view text, std::string_view what) {
  const auto shape_error = [&] {
    return std::invalid_argument(std::string(what) + " '" + std::string(text) +
                                 "' should look like 1.33+1e-8i, 1.33,1e-8 or 1.33");
  };
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  std::string_view s = text;
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  if (s.empty()) throw shape_error();
  // "n,k" or "n k": one separator run, a number on each side.
  const auto sep = s.find_first_of(", \t");
  if (sep != std::string_view::npos) {
    auto rest = s.substr(sep);
    std::size_t skip = 0, commas = 0;
    while (skip < rest.size() && (rest[skip] == ',' || blank(rest[skip]))) commas += rest[skip++] == ',';
    rest.remove_prefix(skip);
    if (commas > 1 || rest.empty() || rest.find_first_of(", \t") != std::string_view::npos) throw shape_error();
    return {std::string(s.substr(0, sep)), std::string(rest)};
  }
  // "n+ki": the sign that starts k is the last one not in an exponent.
  if (s.back() == 'i' || s.back() == 'j') {
    s.remove_suffix(1);
    std::size_t split_at = std::string_view::npos;
    for (std::size_t i = 1; i < s.size(); ++i)
      if ((s[i] == '+' || s[i] == '-') && s[i - 1] != 'e' && s[i - 1] != 'E') split_at = i;
    if (split_at == std::string_view::npos) throw shape_error();
    return {std::string(s.substr(0, split_at)), std::string(s.substr(split_at))};
  }
  return {std::string(s), "0"};
}

std::string index_text(std::complex<double> m) {
  std::ostringstream os;
  os << m.real();
  if (m.imag() != 0) os << "+" << m.imag() << "i";
  return os.str();
}

}  // namespace attenuvis::io
