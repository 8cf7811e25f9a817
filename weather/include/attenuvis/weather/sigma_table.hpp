// sigma over wavelengths x conditions, computed in parallel (TBB), written
// atomically as CSV or JSON.
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/sigma.hpp"

namespace attenuvis::weather {

struct SigmaTable {
  std::vector<double> wavelengths_m;
  std::vector<LabelledCondition> conditions;  // labels: the CSV/JSON "condition" column
  std::vector<Sigma> cells;  // cells[w * conditions.size() + c]
  Settings settings;
  const Sigma& at(std::size_t w, std::size_t c) const { return cells[w * conditions.size() + c]; }
};

// "400:800:10nm" (start:stop:step with one unit at the end), "550nm", "400nm,550nm,10.6um".
std::vector<double> parse_wavelength_list(const std::string& text);

// Every cell is independent; TBB spreads them over the cores (threads: 0 = all).
// Conditions that do not depend on wavelength are still reported per row (cheap).
// Any failing cell makes the whole call throw, naming the cell.
SigmaTable sigma_table(const std::vector<LabelledCondition>& conditions, const std::vector<double>& wavelengths_m,
                       const Settings& settings, int threads = 0);

enum class TableFormat { csv, json };
TableFormat parse_table_format(const std::string& text);
// Writes through attenuvis::io::StagedFile (a temporary renamed onto `path`):
// a failure leaves no partial file.  Every number is finite (sigma() checks
// its results); where sigma = 0 the visibility is unbounded: an empty CSV
// cell, no "visibility_m" member in JSON.
void write_sigma_table(const SigmaTable& t, const std::string& path, TableFormat format, SigmaUnit unit);
std::string format_sigma_table(const SigmaTable& t, TableFormat format, SigmaUnit unit);

}  // namespace attenuvis::weather
