// The writers behind write_sigma_table (sigma_table.hpp), one per format.
// Detail of the library, in a public header only for its tests: the text
// formats are strings here so that a test reads them without a file.
#pragma once

#include <string>

#include "attenuvis/weather/sigma_table.hpp"

namespace attenuvis::weather::detail {

// The CSV, its JSON sidecar, the JSON document (sigma_table_text.cpp).
std::string format_sigma_table_csv(const SigmaTable& t, SigmaUnit unit);
std::string format_sigma_table_sidecar(const SigmaTable& t, SigmaUnit unit, const TableProvenance& provenance);
std::string format_sigma_table_json(const SigmaTable& t, SigmaUnit unit, const TableProvenance& provenance);
// netCDF-4, CF-1.8 (sigma_table_netcdf.cpp).
void write_sigma_table_netcdf(const SigmaTable& t, const std::string& path, SigmaUnit unit,
                              const TableProvenance& provenance);

// The radiative-transfer inputs (sigma_table_rt_inputs.cpp): libRadtran's
// netCDF Mie table, and DISORT's per-layer input as text.
void write_sigma_table_libradtran(const SigmaTable& t, const std::string& path, const TableProvenance& provenance);
std::string format_sigma_table_disort(const SigmaTable& t, const TableProvenance& provenance,
                                      double layer_thickness_m);

}  // namespace attenuvis::weather::detail
