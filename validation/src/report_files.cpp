// Plain-file writers of the report: numbers as text, tables as CSV, the key
// numbers as JSON, and the atomic write every output goes through.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <system_error>


#include "attenuvis/io/number_text.hpp"
#include "attenuvis/io/staged_file.hpp"
#include "attenuvis/validation/report.hpp"

namespace attenuvis::validation {

std::string format_number(double v, int digits) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (v == 0.0) return "0";
  const double a = std::fabs(v);
  char buf[64];
  // Integers that fit are shown whole (node counts, degrees).
  if (a < 1e15 && v == std::floor(v) && a >= 1.0) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  if (a >= 1e-4 && a < 1e7) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    std::string s = buf;
    if (s.find('e') == std::string::npos) return s;
  }
  std::snprintf(buf, sizeof buf, "%.*e", std::max(0, digits - 1), v);
  std::string s = buf;
  // Trim zeros of the mantissa: 3.200e-12 -> 3.2e-12.
  const auto e = s.find('e');
  auto m = s.substr(0, e);
  if (m.find('.') != std::string::npos) {
    while (!m.empty() && m.back() == '0') m.pop_back();
    if (!m.empty() && m.back() == '.') m.pop_back();
  }
  auto ex = s.substr(e + 1);
  const bool neg = ex[0] == '-';
  ex = ex.substr(1);
  while (ex.size() > 1 && ex[0] == '0') ex.erase(0, 1);
  return m + "e" + (neg ? "-" : "") + ex;
}

std::string exact_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return io::shortest(v);
}

void write_file_atomically(const std::string& path, const std::string& text) {
  io::write_file_atomically(path, text);
}

namespace {
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}
}  // namespace

void write_table_csv(const Table& table, const std::string& path) {
  std::ostringstream os;
  for (std::size_t i = 0; i < table.header.size(); ++i) os << (i ? "," : "") << csv_field(table.header[i]);
  os << "\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      os << (i ? "," : "") << (row[i].numeric ? exact_number(row[i].value) : csv_field(row[i].text));
    }
    os << "\n";
  }
  write_file_atomically(path, os.str());
}

void write_key_json(const Report& report, const std::string& path) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, value] : report.key) j[name] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  write_file_atomically(path, j.dump(1) + "\n");
}

}  // namespace attenuvis::validation
