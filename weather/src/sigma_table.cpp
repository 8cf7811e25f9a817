// Parallel sigma tables and their atomic CSV/JSON output.
#include "attenuvis/weather/sigma_table.hpp"

#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "attenuvis/io/staged_file.hpp"
#include "attenuvis/weather/units.hpp"
#include "attenuvis/weather/visibility.hpp"

namespace attenuvis::weather {

std::vector<double> parse_wavelength_list(const std::string& text) {
  std::vector<double> out;
  if (text.find(':') != std::string::npos) {
    // start:stop:step + unit on the step (or on all three).
    std::vector<std::string> f;
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, ':')) f.push_back(part);
    if (f.size() != 3) throw std::invalid_argument("wavelength range '" + text + "' should be START:STOP:STEPunit, e.g. 400:800:10nm");
    std::string unit;
    std::string step = f[2];
    while (!step.empty() && !std::isdigit(static_cast<unsigned char>(step.back())) && step.back() != '.') {
      unit.insert(unit.begin(), step.back());
      step.pop_back();
    }
    if (unit.empty()) throw std::invalid_argument("wavelength range '" + text + "' needs a unit, e.g. 400:800:10nm");
    auto with_unit = [&](const std::string& s) {
      bool has_unit = !s.empty() && std::isalpha(static_cast<unsigned char>(s.back()));
      return parse_wavelength(has_unit ? s : s + unit);
    };
    double a = with_unit(f[0]), b = with_unit(f[1]), h = parse_length(step + unit, "wavelength step");
    if (!(b >= a)) throw std::invalid_argument("wavelength range '" + text + "': STOP must be >= START");
    double n = std::floor((b - a) / h + 1e-9);
    if (n > 100000) throw std::invalid_argument("wavelength range '" + text + "' has too many values");
    for (int i = 0; i <= static_cast<int>(n); ++i) out.push_back(a + i * h);
  } else {
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, ',')) out.push_back(parse_wavelength(part));
  }
  if (out.empty()) throw std::invalid_argument("no wavelengths in '" + text + "'");
  return out;
}

SigmaTable sigma_table(const std::vector<LabelledCondition>& conditions, const std::vector<double>& wavelengths,
                       const Settings& settings, int threads) {
  SigmaTable t;
  t.wavelengths_m = wavelengths;
  t.conditions = conditions;
  t.settings = settings;
  t.cells.resize(wavelengths.size() * conditions.size());
  std::mutex error_mutex;
  std::string first_error;
  auto work = [&] {
    tbb::parallel_for(std::size_t(0), t.cells.size(), [&](std::size_t i) {
      std::size_t w = i / conditions.size(), c = i % conditions.size();
      try {
        t.cells[i] = sigma(conditions[c].condition, wavelengths[w], settings);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(error_mutex);
        std::ostringstream msg;
        msg << "condition '" << conditions[c].label << "' at " << wavelengths[w] * 1e9 << " nm: " << e.what();
        if (first_error.empty()) first_error = msg.str();
      }
    });
  };
  if (threads > 0) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    work();
  } else {
    work();
  }
  if (!first_error.empty()) throw std::runtime_error(first_error);
  return t;
}

TableFormat parse_table_format(const std::string& text) {
  if (text == "csv") return TableFormat::csv;
  if (text == "json") return TableFormat::json;
  throw std::invalid_argument("unknown table format '" + text + "' (csv or json)");
}

namespace {
std::string json_escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    switch (ch) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\t': o += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          o += buf;
        } else {
          o += ch;
        }
    }
  }
  return o;
}
std::string csv_quote(const std::string& s) {
  std::string o = "\"";
  for (char ch : s) o += (ch == '"') ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}
}  // namespace

std::string format_sigma_table(const SigmaTable& t, TableFormat format, SigmaUnit unit) {
  std::ostringstream o;
  o.precision(10);
  std::string u = to_string(unit);
  if (format == TableFormat::csv) {
    o << "# sigma table; units " << u << "; convention " << to_string(t.settings.convention)
      << " (applies to power-law rows); visibility at contrast threshold " << t.settings.contrast_threshold << "\n";
    o << "wavelength_nm,condition,sigma_" << u << ",error_" << u << ",visibility_m,convention,model,note\n";
    for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
      for (std::size_t c = 0; c < t.conditions.size(); ++c) {
        const Sigma& s = t.at(w, c);
        // sigma = 0 has no visibility (unbounded): the cell stays empty, as the JSON omits it.
        std::ostringstream vis;
        vis.precision(10);
        if (s.per_m > 0) vis << koschmieder_visibility_m(s.per_m, t.settings.contrast_threshold);
        o << t.wavelengths_m[w] * 1e9 << "," << csv_quote(t.conditions[c].label) << ","
          << convert_from_per_m(s.per_m, unit) << "," << convert_from_per_m(s.error_per_m, unit) << "," << vis.str() << ","
          << s.convention << "," << csv_quote(s.model) << "," << csv_quote(s.note) << "\n";
      }
  } else {
    o << "{\n  \"units\": \"" << json_escape(u) << "\",\n  \"convention\": \"" << to_string(t.settings.convention)
      << "\",\n  \"contrast_threshold\": " << t.settings.contrast_threshold << ",\n  \"rows\": [\n";
    bool first = true;
    for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
      for (std::size_t c = 0; c < t.conditions.size(); ++c) {
        const Sigma& s = t.at(w, c);
        o << (first ? "" : ",\n") << "    {\"wavelength_nm\": " << t.wavelengths_m[w] * 1e9 << ", \"condition\": \""
          << json_escape(t.conditions[c].label) << "\", \"sigma\": " << convert_from_per_m(s.per_m, unit)
          << ", \"error\": " << convert_from_per_m(s.error_per_m, unit);
        if (s.per_m > 0) o << ", \"visibility_m\": " << koschmieder_visibility_m(s.per_m, t.settings.contrast_threshold);
        o << ", \"convention\": \"" << s.convention << "\", \"model\": \"" << json_escape(s.model)
          << "\", \"note\": \"" << json_escape(s.note) << "\"}";
        first = false;
      }
    o << "\n  ]\n}\n";
  }
  return o.str();
}

void write_sigma_table(const SigmaTable& t, const std::string& path, TableFormat format, SigmaUnit unit) {
  io::write_file_atomically(path, format_sigma_table(t, format, unit));
}

}  // namespace attenuvis::weather
