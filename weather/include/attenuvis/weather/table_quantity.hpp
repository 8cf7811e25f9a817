// What a sigma table can hold: the quantities (one registry, read by every
// output format and by --help) and the parameter each condition is set by.
//
// Each quantity has a name (the CSV column, the JSON member, the netCDF
// variable), the name Python's table() takes it by, a kind that fixes its
// unit, a long name and, where the CF standard-name table has one that fits
// hydrometeors, a standard name.  A new quantity is one enum value, one
// registry row (table_quantity.cpp) and one case in table_value
// (sigma_table.cpp); the writers, --help and Python need nothing more.  A
// quantity of a new unit adds a QuantityKind and its cases in the four unit
// functions below; one on a further axis (as the Legendre moments and the
// phase function on angles are) adds that dimension to the writers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather {

// The quantities a table can hold (moments and the phase function aside).
enum class Quantity { sigma_ext, sigma_sca, sigma_abs, ssa, g, backscatter, lidar_ratio };

// What unit a quantity takes in a table.
enum class QuantityKind {
  coefficient,    // an attenuation coefficient: 1/m, 1/km or dB/km as the table's unit says
  dimensionless,  // a ratio (single-scattering albedo, asymmetry parameter): unit 1
  // A coefficient per steradian (the volume backscatter coefficient): 1/(m sr)
  // or 1/(km sr) as the table's length unit says; a dB/km table writes it per
  // km (decibels describe attenuation, not a backscatter coefficient).
  coefficient_per_sr,
  steradian,      // the lidar (extinction-to-backscatter) ratio: sr
};

// A quantity's names, kind and descriptions, as every output writes them.
struct QuantityInfo {
  Quantity id;
  std::string name;           // "sigma_ext"
  // Python's name (attenuvis.weather.table): the attribute of its Optics
  // result that holds the value ("scattering", "albedo"), "sigma" for sigma_ext.
  std::string python_name;
  QuantityKind kind;
  std::string long_name;      // "volume extinction coefficient"
  std::string standard_name;  // CF standard name, "" where CF has none that fits
  std::string comment;        // why there is no standard name, where one might be expected
  bool needs_size_distribution;  // only Mie conditions have it; other rows are empty
};

// Every quantity, in the order of the enum.
const std::vector<QuantityInfo>& table_quantities();
const QuantityInfo& info(Quantity q);
// "sigma_ext,ssa,g": names from table_quantities(), each at most once.  Throws
// std::invalid_argument naming the unknown or repeated name and listing the known ones.
std::vector<Quantity> parse_quantity_list(const std::string& text);
// What --quantities asks for: the named quantities, the Legendre moments
// chi_0..chi_L of the phase function when the list holds "moments:L" (L in
// [0, kMaxTableMoment]; -1: none), and the bulk phase function on an angle
// grid when it holds "phase" (the grid is the caller's: sigma_table's
// angles_deg).  "moments:L" or "phase" alone is a valid list.
constexpr int kMaxTableMoment = 1000;
struct QuantityRequest {
  std::vector<Quantity> quantities;
  int max_moment = -1;
  bool phase = false;
};
QuantityRequest parse_quantity_request(const std::string& text);
// The names joined by ", " (help text, messages).
std::string quantity_names();

// The unit of a quantity in a table written in `unit`, as text ("1/km", "1")
// and as UDUNITS text for netCDF ("km-1", "1"); dB/km has no UDUNITS spelling.
std::string unit_text(QuantityKind kind, SigmaUnit unit);
std::optional<std::string> udunits_text(QuantityKind kind, SigmaUnit unit);
// The column-name suffix of a unit: "per_m", "per_km", "dB_per_km".
std::string unit_suffix(SigmaUnit unit);
// What the writers need of a kind: the column suffix ("_per_km"; "" for a
// ratio) and a value in SI converted to the table's unit (NaN stays NaN).
std::string column_suffix(QuantityKind kind, SigmaUnit unit);
double in_table_unit(QuantityKind kind, double value, SigmaUnit unit);

// The number a condition is set by (and that a sweep varies): the rain or
// snow rate, a visibility, a given sigma or an aerosol's relative humidity.
// Conditions set by nothing (clear, the fog presets, a distribution file)
// have none.
enum class ParameterKind { rate, visibility, given_sigma, relative_humidity };
// Every kind, in the order of the enum (the tables' columns follow it).
const std::vector<ParameterKind>& parameter_kinds();
struct ConditionParameter {
  ParameterKind kind;
  double value;  // mm/h, m, or 1/m
};
std::optional<ConditionParameter> condition_parameter(const Condition& c);

// The names and units of a condition parameter's column or variable.
struct ParameterInfo {
  ParameterKind kind;
  std::string name;           // base of the column / variable name: "rate", "visibility", "given_sigma"
  std::string long_name;
  std::string standard_name;  // CF standard name or ""
  std::string unit;           // "mm/h", "m"; empty for given_sigma (it follows the table's unit)
  std::string udunits;        // "mm h-1", "m"; empty for given_sigma
  std::string column_suffix;  // of the CSV column: "mm_h", "m", "percent"; empty for given_sigma
};
// The registry entry of a parameter kind.
const ParameterInfo& info(ParameterKind k);

}  // namespace attenuvis::weather
