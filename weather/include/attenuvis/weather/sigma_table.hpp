// Optical quantities over wavelengths x conditions, computed in parallel
// (TBB), written atomically as CSV (with a JSON sidecar), JSON or netCDF-4.
//
// sigma_ext is sigma() (sigma.hpp): for an analytic drop distribution the
// contour integral, otherwise the real-axis quadrature.  The quantities that
// need the whole single-scattering result (sigma_sca, sigma_abs, ssa, g) come
// from condition_bulk_optics(), the real-axis quadrature, computed only when
// one of them is asked for; the backscatter coefficient and lidar ratio, the
// Legendre moments and the phase function on an angle grid come from
// condition_optics() (the moments and the phase function from its second
// pass: per drop, O(x^2) for the moments, O(x) per angle), only when asked
// for, and then the others come from its first pass; an aerosol's come from
// one set of integrals (aerosol_optics.hpp), sigma_ext too.  Only Mie
// conditions and aerosols have particles:
// for every other condition (power laws, visibility models, clear air, a
// given sigma) those quantities are missing — an empty CSV cell, JSON null,
// the netCDF _FillValue — and so are they where the integral used the
// large-sphere expansion of Q_ext (rain drops beyond x = 2000), which gives
// no Q_sca.  Asking for them is not an error: a table may mix both kinds.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "attenuvis/weather/table_quantity.hpp"

namespace attenuvis::weather {

// One wavelength x condition of a table.
struct TableCell {
  Sigma sigma;                       // always
  std::optional<BulkOptics> optics;  // Mie conditions, when a quantity needs it
};

// A value and its error estimate in SI (1/m for coefficients); NaN where the
// quantity does not exist for the cell (see above).
struct QuantityValue {
  double value, error;
};

// A table of quantities over wavelengths x conditions.
struct SigmaTable {
  std::vector<double> wavelengths_m;
  std::vector<LabelledCondition> conditions;  // labels: the "condition" column
  std::vector<Quantity> quantities;           // in the order asked for
  int max_moment = -1;                        // >= 0: Legendre moments chi_0..chi_L of Mie cells
  std::vector<double> angles_deg;             // non-empty: the bulk phase function of Mie cells there
  std::vector<TableCell> cells;               // cells[w * conditions.size() + c]
  Settings settings;
  const TableCell& at(std::size_t w, std::size_t c) const { return cells[w * conditions.size() + c]; }
};

// The value and error of one quantity in a cell, or missing.
QuantityValue table_value(const TableCell& cell, Quantity q);
// The cells whose values missed Settings::rel_tolerance (their errors are
// those reached), in table order, each as "LABEL at LAMBDA nm: SHORTFALL".
std::vector<std::string> cells_short_of_tolerance(const SigmaTable& t);
// The labels of the conditions with a missing value of some asked-for
// quantity at some wavelength, in table order.
std::vector<std::string> conditions_with_missing_values(const SigmaTable& t);
// The rule above in one sentence, for the outputs' metadata.
std::string missing_value_rule();
// A table wavelength in nm as the outputs write it: 12 significant digits,
// so a grid built in metres prints 550, not 550.0000000000001.
double wavelength_nm(double wavelength_m);

// "400:800:10nm" (start:stop:step with one unit at the end; STOP is included
// when it lies on the grid, within 1e-6 STEP), "550nm", "400nm,550nm,10.6um".
std::vector<double> parse_wavelength_list(const std::string& text);

// Every cell is independent; TBB spreads them over the cores (threads: 0 = all).
// Conditions that do not depend on wavelength are still reported per row (cheap).
// Any failing cell makes the whole call throw, naming the cell.
// angles_deg: the bulk phase function at these scattering angles (degrees,
// strictly increasing, each in [0, 180]: the netCDF angle coordinate), as
// condition_optics computes it; empty: none.  A bad grid throws
// std::invalid_argument naming the angle before any work.
SigmaTable sigma_table(const std::vector<LabelledCondition>& conditions, const std::vector<double>& wavelengths_m,
                       const Settings& settings, int threads = 0,
                       const std::vector<Quantity>& quantities = {Quantity::sigma_ext}, int max_moment = -1,
                       const std::vector<double>& angles_deg = {});
// What sigma_table asks of angles_deg; throws std::invalid_argument naming the first bad angle.
void check_table_angles(const std::vector<double>& angles_deg);
// chi_l of a cell and its error; NaN where the cell has no moments (a
// condition without drops, or rain's large-x expansion).
QuantityValue table_moment(const TableCell& cell, int l);
// p(theta_i) of a cell at the table's i-th angle and its error, normalised
// as phase_function_normalisation() says; NaN where the cell has no phase
// function (as table_moment).
QuantityValue table_phase(const TableCell& cell, std::size_t angle_index);
// "int p dOmega = 4 pi ...": the normalisation every output names.
std::string phase_function_normalisation();
// The CSV column of the phase function at an angle: "phase_10deg",
// "phase_0.5deg" (the angle as the shortest text that reads back to it).
std::string phase_column_name(double angle_deg);

// csv, json, netcdf: every quantity asked for, over wavelengths x conditions.
// libradtran: the netCDF table uvspec reads with wc_properties / ic_properties
// (the layout of libRadtran's mie tool), one effective radius per Mie
// condition; disort: DTAUC, SSALB and PMOM per cell as plain text
// (sigma_table_rt_inputs.cpp says how each maps to attenuvis's quantities).
enum class TableFormat { csv, json, netcdf, libradtran, disort };
TableFormat parse_table_format(const std::string& text);  // "csv" | "json" | "netcdf" | "libradtran" | "disort"

// What the radiative-transfer formats need besides the table.
struct TableWriteOptions {
  double layer_thickness_m = 1000;  // disort: DTAUC = sigma_ext x this
};

// What every output says about where it came from.
struct TableProvenance {
  std::string producer;  // "attenuvis 0.1.0 (commit abc1234)"
};

// The sidecar of a CSV table: "<csv path>.meta.json".
std::string csv_sidecar_path(const std::string& csv_path);

// Writes through attenuvis::io::StagedFile(s) (temporaries renamed onto the
// paths): a failure leaves no partial file.  CSV writes the table and its
// sidecar together (both or neither).  Every number is finite or missing;
// where sigma_ext = 0 the Koschmieder visibility is unbounded: missing too.
// netCDF refuses SigmaUnit::dB_per_km (no UDUNITS spelling; CF needs one).
// libradtran and disort need the Legendre moments (max_moment >= 0) of every
// cell, hence Mie conditions only, and write in their own units whatever
// `unit` says; libradtran also needs effective radii on an equidistant grid
// (uvspec interpolates in them) and one refractive index per wavelength.  Each
// refusal says what to change.  The writer of each format:
// detail/sigma_table_formats.hpp.
void write_sigma_table(const SigmaTable& t, const std::string& path, TableFormat format, SigmaUnit unit,
                       const TableProvenance& provenance, const TableWriteOptions& options = {});

}  // namespace attenuvis::weather
