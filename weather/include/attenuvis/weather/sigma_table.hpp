// sigma over wavelengths x conditions, computed in parallel (TBB), written
// atomically as CSV or JSON.
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/sigma.hpp"

namespace attenuvis::weather {

struct SigmaTable {
  std::vector<double> wavelengths_m;
  std::vector<Condition> conditions;
  std::vector<Sigma> cells;  // cells[w * conditions.size() + c]
  Settings settings;         // wavelength_m unused
  const Sigma& at(std::size_t w, std::size_t c) const { return cells[w * conditions.size() + c]; }
};

// "400:800:10nm" (start:stop:step with one unit at the end), "550nm", "400nm,550nm,10.6um".
std::vector<double> parse_wavelength_list(const std::string& text);

// Every cell is independent; TBB spreads them over the cores (threads: 0 = all).
// Conditions that do not depend on wavelength are still reported per row (cheap).
// Any failing cell makes the whole call throw, naming the cell.
SigmaTable sigma_table(const std::vector<Condition>& conditions, const std::vector<double>& wavelengths_m,
                       const Settings& settings, int threads = 0);

enum class TableFormat { csv, json };
TableFormat parse_table_format(const std::string& text);
// Writes to a temporary file in the target's directory, then renames it over
// `path`: a failure leaves no partial file.
void write_sigma_table(const SigmaTable& t, const std::string& path, TableFormat format, SigmaUnit unit);
std::string format_sigma_table(const SigmaTable& t, TableFormat format, SigmaUnit unit);

// Atomic write of a whole text (shared by the CLI for other outputs).
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace attenuvis::weather
