#include "attenuvis/io/number_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace attenuvis::io {

double parse_double(std::string_view text, std::string_view what) {
  const std::string quoted = std::string(what) + ": '" + std::string(text) + "'";
  if (text.empty()) throw std::invalid_argument(std::string(what) + ": a number is missing");
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (*begin == '+') ++begin;  // from_chars takes no leading '+'
  double value = 0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range)
    throw std::invalid_argument(quoted + " is out of the range of a double");
  if (ec != std::errc() || ptr != end) throw std::invalid_argument(quoted + " is not a number");
  if (!std::isfinite(value)) throw std::invalid_argument(quoted + " is not finite");
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

std::string index_text(std::complex<double> m) {
  std::ostringstream os;
  os << m.real();
  if (m.imag() != 0) os << "+" << m.imag() << "i";
  return os.str();
}

}  // namespace attenuvis::io
