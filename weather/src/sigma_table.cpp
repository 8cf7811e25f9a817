// Parallel tables of optical quantities; the choice of output format.
#include "attenuvis/weather/sigma_table.hpp"

#include "attenuvis/weather/detail/sigma_table_formats.hpp"

#include "attenuvis/weather/aerosol_optics.hpp"
#include "attenuvis/weather/cancel.hpp"
#include "attenuvis/weather/condition_optics.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/io/staged_file.hpp"
#include "attenuvis/weather/units.hpp"

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
    // STOP is on the grid when within 1e-6 STEP of it (rounding of the decimal inputs).
    double n = std::floor((b - a) / h + 1e-6);
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

double wavelength_nm(double wavelength_m) { return std::stod(io::significant(wavelength_m * 1e9, 12)); }

std::string missing_value_rule() {
  return "sigma_sca, sigma_abs, ssa, g, backscatter, lidar_ratio, the Legendre moments and the phase function "
         "exist only for Mie conditions and aerosols (particles): they are missing "
         "for power laws, visibility models, clear air and a given sigma, and where the integral used the "
         "large-sphere expansion of Q_ext (rain drops beyond x = 2000), which gives no Q_sca; "
         "the Koschmieder visibility is missing where sigma_ext = 0 (unbounded)";
}

QuantityValue table_value(const TableCell& cell, Quantity q) {
  constexpr double missing = std::numeric_limits<double>::quiet_NaN();
  if (q == Quantity::sigma_ext) return {cell.sigma.per_m, cell.sigma.error_per_m};
  // Only Mie conditions have optics; the large-x expansion of Q_ext (rain) gives no Q_sca.
  if (!cell.optics || !cell.optics->scattering_computed) return {missing, missing};
  const BulkOptics& b = *cell.optics;
  switch (q) {
    case Quantity::sigma_ext: break;
    case Quantity::sigma_sca: return {b.scattering.value, b.scattering.error()};
    case Quantity::sigma_abs: return {b.absorption.value, b.absorption.error()};
    case Quantity::ssa: return {b.albedo, b.albedo_error};
    case Quantity::g: return {b.asymmetry, b.asymmetry_error};
    case Quantity::backscatter:
      if (!b.backscatter_computed) break;
      return {b.backscatter.value, b.backscatter.error()};
    case Quantity::lidar_ratio:
      if (!b.backscatter_computed) break;
      return {b.lidar_ratio, b.lidar_ratio_error};
  }
  return {missing, missing};
}

QuantityValue table_moment(const TableCell& cell, int l) {
  constexpr double missing = std::numeric_limits<double>::quiet_NaN();
  if (!cell.optics || !cell.optics->scattering_computed || l < 0 ||
      static_cast<std::size_t>(l) >= cell.optics->moments.size())
    return {missing, missing};
  return {cell.optics->moments[static_cast<std::size_t>(l)], cell.optics->moments_error[static_cast<std::size_t>(l)]};
}

QuantityValue table_phase(const TableCell& cell, std::size_t i) {
  constexpr double missing = std::numeric_limits<double>::quiet_NaN();
  if (!cell.optics || !cell.optics->scattering_computed || i >= cell.optics->phase.size()) return {missing, missing};
  return {cell.optics->phase[i], cell.optics->phase_error[i]};
}

std::string phase_function_normalisation() {
  return "int p dOmega = 4 pi over the sphere (isotropic scattering: p = 1; divide by 4 pi for 1/sr; "
         "(1/2) int p dmu = 1 over mu = cos theta in [-1, 1])";
}

std::string phase_column_name(double angle_deg) { return "phase_" + io::shortest(angle_deg) + "deg"; }

// A table's angles are the netCDF coordinate of the angle dimension: each in
// [0, 180] and strictly increasing (NUG and CF 1.8 sec. 1.3: a coordinate
// variable is monotonic), which also keeps the CSV's column names unique.
void check_table_angles(const std::vector<double>& angles) {
  check_scattering_angles(angles);
  for (std::size_t i = 1; i < angles.size(); ++i) {
    const double a = angles[i];
    if (!(a > angles[i - 1]))
      throw std::invalid_argument("scattering angle " + std::to_string(i + 1) + " (" + io::shortest(a) +
                                  " deg) does not increase on the one before (" + io::shortest(angles[i - 1]) +
                                  " deg): a table's angles are a coordinate, each listed once, in increasing order");
  }
}

std::vector<std::string> cells_short_of_tolerance(const SigmaTable& t) {
  std::vector<std::string> out;
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      const TableCell& cell = t.at(w, c);
      std::string shortfall = cell.sigma.shortfall;
      if (shortfall.empty() && cell.optics) shortfall = cell.optics->shortfall;
      if (!shortfall.empty())
        out.push_back(t.conditions[c].label + " at " + io::significant(wavelength_nm(t.wavelengths_m[w]), 12) +
                      " nm: " + shortfall);
    }
  return out;
}

std::vector<std::string> conditions_with_missing_values(const SigmaTable& t) {
  std::vector<std::string> out;
  for (std::size_t c = 0; c < t.conditions.size(); ++c) {
    bool missing = false;
    for (std::size_t w = 0; w < t.wavelengths_m.size() && !missing; ++w) {
      for (Quantity q : t.quantities) missing = missing || std::isnan(table_value(t.at(w, c), q).value);
      if (t.max_moment >= 0) missing = missing || std::isnan(table_moment(t.at(w, c), 0).value);
      if (!t.angles_deg.empty()) missing = missing || std::isnan(table_phase(t.at(w, c), 0).value);
    }
    if (missing) out.push_back(t.conditions[c].label);
  }
  return out;
}

SigmaTable sigma_table(const std::vector<LabelledCondition>& conditions, const std::vector<double>& wavelengths,
                       const Settings& settings, int threads, const std::vector<Quantity>& quantities,
                       int max_moment, const std::vector<double>& angles_deg) {
  check_table_angles(angles_deg);
  SigmaTable t;
  t.wavelengths_m = wavelengths;
  t.conditions = conditions;
  t.quantities = quantities;
  t.max_moment = max_moment;
  t.angles_deg = angles_deg;
  t.settings = settings;
  t.settings.cancel = nullptr;  // the flag belongs to this call; the table outlives it
  t.cells.resize(wavelengths.size() * conditions.size());
  // The angular quantities (moments, phase function) cost O(x^2) per drop: only when asked.
  const bool needs_angular = max_moment >= 0 || !angles_deg.empty();
  const bool needs_optics = needs_angular || std::any_of(quantities.begin(), quantities.end(), [](Quantity q) {
                               return info(q).needs_size_distribution;
                             });
  const bool needs_backscatter = std::any_of(quantities.begin(), quantities.end(), [](Quantity q) {
    return q == Quantity::backscatter || q == Quantity::lidar_ratio;
  });
  OpticsRequest request;
  request.backscatter = needs_backscatter;
  request.legendre_moments = max_moment;
  request.angles_deg = angles_deg;
  std::mutex error_mutex;
  std::string first_error;
  std::atomic<bool> cancelled{false};
  auto work = [&] {
    tbb::parallel_for(std::size_t(0), t.cells.size(), [&](std::size_t i) {
      std::size_t w = i / conditions.size(), c = i % conditions.size();
      try {
        throw_if_cancelled(settings.cancel);  // once per cell: cells without Mie work never look otherwise
        if (const auto* aerosol = std::get_if<AerosolCondition>(&conditions[c].condition); aerosol && needs_optics) {
          // sigma and the rest from one set of integrals (aerosol_optics.hpp).
          const AerosolOptics o = aerosol_optics(*aerosol, wavelengths[w], settings, request);
          t.cells[i].sigma = aerosol_sigma(o);
          t.cells[i].optics = o.bulk;
          return;
        }
        t.cells[i].sigma = sigma(conditions[c].condition, wavelengths[w], settings);
        if (const auto* mie = std::get_if<MieCondition>(&conditions[c].condition); mie && needs_optics)
          t.cells[i].optics = needs_backscatter || needs_angular
                                  ? condition_optics(*mie, wavelengths[w], settings, request).bulk
                                  : condition_bulk_optics(*mie, wavelengths[w], settings);
      } catch (const Cancelled&) {
        cancelled = true;  // a requested stop, reported as such below (not as a failing cell)
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(error_mutex);
        std::ostringstream msg;
        msg << "condition '" << conditions[c].label << "' at " << io::shortest(wavelengths[w] * 1e9)
            << " nm: " << e.what();
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
  if (cancelled) throw Cancelled();
  if (!first_error.empty()) throw std::runtime_error(first_error);
  return t;
}

TableFormat parse_table_format(const std::string& text) {
  if (text == "csv") return TableFormat::csv;
  if (text == "json") return TableFormat::json;
  if (text == "netcdf") return TableFormat::netcdf;
  if (text == "libradtran") return TableFormat::libradtran;
  if (text == "disort") return TableFormat::disort;
  throw std::invalid_argument("unknown table format '" + text + "' (csv, json, netcdf, libradtran or disort)");
}

std::string csv_sidecar_path(const std::string& csv_path) { return csv_path + ".meta.json"; }

void write_sigma_table(const SigmaTable& t, const std::string& path, TableFormat format, SigmaUnit unit,
                       const TableProvenance& provenance, const TableWriteOptions& options) {
  switch (format) {
    case TableFormat::csv: {
      io::StagedFiles files;
      files.add(path).write(detail::format_sigma_table_csv(t, unit));
      files.add(csv_sidecar_path(path)).write(detail::format_sigma_table_sidecar(t, unit, provenance));
      files.commit_all();
      return;
    }
    case TableFormat::json: io::write_file_atomically(path, detail::format_sigma_table_json(t, unit, provenance)); return;
    case TableFormat::netcdf: detail::write_sigma_table_netcdf(t, path, unit, provenance); return;
    case TableFormat::libradtran: detail::write_sigma_table_libradtran(t, path, provenance); return;
    case TableFormat::disort:
      io::write_file_atomically(path, detail::format_sigma_table_disort(t, provenance, options.layer_thickness_m));
      return;
  }
}

}  // namespace attenuvis::weather
