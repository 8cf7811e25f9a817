// attenuvis sigma | table | distribution: argument parsing only; the work is
// in attenuvis::weather.
#include <iostream>
#include <sstream>

#include <boost/math/constants/constants.hpp>

#include <nlohmann/json.hpp>

#include "attenuvis/weather.hpp"
#include "build_info.hpp"
#include "command_help.hpp"
#include "commands.hpp"
#include "path_clashes.hpp"
#include "weather_options.hpp"

namespace attenuvis::cli {
namespace {

namespace w = attenuvis::weather;

// Options of sigma and table: the shared weather options and the output unit.
struct CommonOptions {
  WeatherOptions weather;
  std::string units = "m";
};

void add_common(CLI::App* cmd, CommonOptions& o, WeatherOptionSet which) {
  cmd->add_option("--units", o.units, "sigma units: m (1/m), km (1/km) or dB/km")->capture_default_str();
  add_weather_options(cmd, o.weather, which);
}

std::string num(double v, int precision = 6) {
  std::ostringstream o;
  o.precision(precision);
  o << v;
  return o.str();
}

void run_sigma(const std::vector<std::string>& conditions, const CommonOptions& o, bool json) {
  const w::Settings s = weather_settings(o.weather);
  const double wavelength_m = cli::wavelength_m(o.weather);
  w::SigmaUnit unit = w::parse_sigma_unit(o.units);
  std::vector<w::LabelledCondition> parsed;
  for (const auto& text : conditions) parsed.push_back({text, w::parse_condition(text)});  // all parse before any work
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : parsed) {
    w::Sigma r = w::sigma(c.condition, wavelength_m, s);
    // An error above the tolerance asked is printed as reached, and said so.
    if (!r.shortfall.empty()) std::cerr << "warning: " << c.label << ": " << r.shortfall << "\n";
    // sigma = 0: the visibility is unbounded (JSON null, "unbounded" in text).
    const bool bounded = r.per_m > 0;
    const double vis = bounded ? w::koschmieder_visibility_m(r.per_m, s.contrast_threshold) : 0.0;
    if (json) {
      // Every sigma-like number of the output in the unit asked for, the error's parts included.
      nlohmann::json terms = nlohmann::json::object();
      for (const auto& e : r.error_terms) terms[e.name] = w::convert_from_per_m(e.per_m, unit);
      nlohmann::json row = {{"condition", c.label},
                            {"wavelength_nm", wavelength_m * 1e9},
                            {"sigma", w::convert_from_per_m(r.per_m, unit)},
                            {"error", w::convert_from_per_m(r.error_per_m, unit)},
                            {"error_terms", terms},
                            {"units", w::to_string(unit)},
                            {"convention", r.convention},
                            {"contrast_threshold", s.contrast_threshold},
                            {"model", r.model},
                            {"note", r.note},
                            {"tolerance_met", r.shortfall.empty()}};
      if (bounded) row["visibility_m"] = vis;
      else row["visibility_m"] = nullptr;
      out.push_back(row);
    } else {
      std::cout << c.label << ": sigma = " << num(w::convert_from_per_m(r.per_m, unit), 10) << " +- "
                << num(w::convert_from_per_m(r.error_per_m, unit), 3) << " " << w::to_string(unit)
                << " at " << num(wavelength_m * 1e9) << " nm, convention " << r.convention << ", visibility "
                << (bounded ? num(vis) + " m" : std::string("unbounded")) << " (contrast " << num(100 * s.contrast_threshold)
                << " %)\n"
                << "  model: " << r.model << "\n";
      if (!r.error_terms.empty()) {
        std::cout << "  error:";
        for (std::size_t i = 0; i < r.error_terms.size(); ++i)
          std::cout << (i ? " + " : " ") << r.error_terms[i].name << " "
                    << num(w::convert_from_per_m(r.error_terms[i].per_m, unit), 3);
        std::cout << " " << w::to_string(unit) << "\n";
      }
      if (!r.note.empty()) std::cout << "  note: " << r.note << "\n";
    }
  }
  if (json) std::cout << out.dump(2) << "\n";
}

// The files the conditions read, size distributions and indices (inputs no output may replace).
std::vector<NamedPath> condition_inputs(const std::vector<w::LabelledCondition>& conditions) {
  std::vector<NamedPath> out;
  for (const auto& c : conditions)
    if (const auto* mie = std::get_if<w::MieCondition>(&c.condition)) {
      if (const auto* file = std::get_if<w::DistributionFile>(&mie->drops)) out.push_back({"fog:file=", file->path});
      if (const auto* index = std::get_if<w::IndexFile>(&mie->index)) out.push_back({"index=", index->path});
    }
  return out;
}

// build_info()'s lines (version, commit, build type, libraries) as one line, runs of blanks squeezed.
std::string producer() {
  std::string out;
  std::istringstream lines(build_info());
  for (std::string line; std::getline(lines, line);) {
    std::string squeezed;
    for (char ch : line)
      if (ch != ' ' || squeezed.empty() || squeezed.back() != ' ') squeezed += ch;
    out += (out.empty() ? "" : "; ") + squeezed;
  }
  return out;
}

struct TableOptions {
  std::string conditions, wavelengths = "550nm", quantities = "sigma_ext", format = "csv", out;
  std::string angles;  // empty: the default grid, when phase is asked for
  std::string layer_thickness = "1km";  // disort: DTAUC = sigma_ext x this
  int threads = 0;
};

// The phase function's angles when --quantities holds phase and --angles is
// not given: every degree, as `mie --phase 0:180:1`.  A fog's forward peak
// (width ~ 1/x rad, a fraction of a degree at 550 nm) needs a finer grid
// near 0: give one with --angles.
constexpr const char* kDefaultTableAngles = "0:180:1";
// Two CSV columns per angle: a bound that keeps a mistyped step from writing
// a table no reader wants.
constexpr std::size_t kMaxTableAngles = 10000;

// The angle grid of a table: --angles, the default with phase, none without.
std::vector<double> table_angles(const TableOptions& t, bool phase) {
  if (!phase) {
    if (!t.angles.empty())
      throw std::invalid_argument("--angles '" + t.angles +
                                  "' sets the phase function's angles: add phase to --quantities, e.g. "
                                  "--quantities sigma_ext,phase");
    return {};
  }
  const std::string text = t.angles.empty() ? kDefaultTableAngles : t.angles;
  std::vector<double> angles = angle_list("--angles", text, kMaxTableAngles);
  try {
    w::check_table_angles(angles);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--angles '" + text + "': " + e.what());
  }
  return angles;
}

void run_table(const TableOptions& t, const CommonOptions& o) {
  const w::Settings s = weather_settings(o.weather);
  std::vector<w::LabelledCondition> parsed;
  for (const auto& text : w::split_condition_list(t.conditions)) {
    auto expanded = w::expand_conditions(text);
    parsed.insert(parsed.end(), expanded.begin(), expanded.end());
  }
  if (parsed.empty()) throw std::invalid_argument("--conditions is empty\n" + w::condition_grammar());
  const auto table_format = w::parse_table_format(t.format);
  // A CSV table writes its sidecar beside it: neither may replace an input.
  std::vector<NamedPath> outputs = {{"--out", t.out}};
  if (table_format == w::TableFormat::csv) outputs.push_back({"--out's sidecar", w::csv_sidecar_path(t.out)});
  refuse_path_clashes(outputs, condition_inputs(parsed));
  const auto unit = w::parse_sigma_unit(o.units);
  if (table_format == w::TableFormat::netcdf && unit == w::SigmaUnit::dB_per_km)
    throw std::invalid_argument("--units dB/km: netCDF tables take --units m or km (CF units must be UDUNITS units)");
  const auto request = [&] {
    try {
      return w::parse_quantity_request(t.quantities);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--quantities: ") + e.what());
    }
  }();
  const auto wavelengths_m = [&] {
    try {
      return w::parse_wavelength_list(t.wavelengths);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--wavelengths: ") + e.what());
    }
  }();
  const std::vector<double> angles = table_angles(t, request.phase);
  auto table = w::sigma_table(parsed, wavelengths_m, s, t.threads, request.quantities, request.max_moment, angles);
  w::TableWriteOptions write_options;
  try {
    write_options.layer_thickness_m = w::parse_distance(t.layer_thickness);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--layer-thickness: ") + e.what());
  }
  w::write_sigma_table(table, t.out, table_format, unit, {producer()}, write_options);
  std::vector<std::string> what;
  if (!request.quantities.empty()) what.push_back(std::to_string(request.quantities.size()) + " quantities");
  if (request.max_moment >= 0) what.push_back("moments 0.." + std::to_string(request.max_moment));
  if (!angles.empty()) what.push_back("the phase function at " + std::to_string(angles.size()) + " angles");
  std::cout << "wrote ";
  for (std::size_t i = 0; i < what.size(); ++i) std::cout << (i == 0 ? "" : " and ") << what[i];
  std::cout << " x " << table.wavelengths_m.size() << " wavelengths x " << parsed.size() << " conditions to "
            << t.out;
  if (table_format == w::TableFormat::csv) std::cout << " (column descriptions in " << w::csv_sidecar_path(t.out) << ")";
  std::cout << "\n";
  // Cells whose errors, as written, exceed the tolerance asked.
  const auto short_of = w::cells_short_of_tolerance(table);
  if (!short_of.empty())
    std::cerr << "warning: " << short_of.size() << " of " << table.cells.size()
              << " cells missed the requested tolerance (their errors are written as reached); the first: "
              << short_of.front() << "\n";
  // Say which conditions leave quantities missing, so an empty column is no surprise.
  const auto missing = w::conditions_with_missing_values(table);
  if (!missing.empty()) {
    std::cout << "note: " << missing.size() << " of " << parsed.size()
              << " conditions have missing values (quantities beyond sigma_ext need a size distribution; see "
                 "missing_values in the metadata):";
    for (std::size_t i = 0; i < missing.size() && i < 5; ++i) std::cout << " " << missing[i];
    std::cout << (missing.size() > 5 ? " ...\n" : "\n");
  }
}

void run_distribution(const std::string& what, const std::string& density_text, bool json) {
  double density = 0;
  try {
    density = w::read_in(w::domain::bulk_density, density_text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--bulk-density: ") + e.what());
  }
  w::SizeDistribution d = w::is_preset_distribution(what) ? w::preset_distribution(what)
                                                          : w::read_distribution_csv(what);
  w::Moments m = w::moments(d, density);
  auto support = d.support(2.0, 1e-12);
  // The domains of the presets and of file values keep these finite; a
  // distribution that escapes them is an error, never a printed NaN.
  const bool ok = std::isfinite(m.number_per_m3) && m.number_per_m3 > 0 && std::isfinite(m.water_content_kg_m3) &&
                  m.water_content_kg_m3 > 0 && std::isfinite(m.effective_radius_m) && m.effective_radius_m > 0 &&
                  std::isfinite(m.mean_radius_m) && std::isfinite(m.mode_radius_m) &&
                  std::isfinite(support.total_moment) && support.total_moment > 0;
  if (!ok)
    throw std::runtime_error("distribution '" + what + "': its moments are not finite and positive (N = " +
                             num(m.number_per_m3 * 1e-6) + " cm^-3, water content " +
                             num(m.water_content_kg_m3 * 1e3) + " g/m^3, effective radius " +
                             num(m.effective_radius_m * 1e6) + " um); its values lie outside what double "
                             "precision can integrate");
  if (json) {
    nlohmann::json out = {{"distribution", d.describe()},
                          {"number_per_cm3", m.number_per_m3 * 1e-6},
                          {"water_content_g_per_m3", m.water_content_kg_m3 * 1e3},
                          {"bulk_density_kg_per_m3", density},
                          {"effective_radius_um", m.effective_radius_m * 1e6},
                          {"mode_radius_um", m.mode_radius_m * 1e6},
                          {"mean_radius_um", m.mean_radius_m * 1e6},
                          {"r2_support_um", {support.breakpoints_m.front() * 1e6, support.breakpoints_m.back() * 1e6}},
                          {"geometric_cross_section_per_m", boost::math::constants::pi<double>() * support.total_moment},
                          {"checks_passed", ok}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "distribution: " << d.describe() << "\n"
              << "  N                 = " << num(m.number_per_m3 * 1e-6, 8) << " cm^-3\n"
              << "  water content     = " << num(m.water_content_kg_m3 * 1e3, 8) << " g/m^3 (bulk density "
              << density << " kg/m^3)\n"
              << "  effective radius  = " << num(m.effective_radius_m * 1e6, 8) << " um (<r^3>/<r^2>)\n"
              << "  mode radius       = " << num(m.mode_radius_m * 1e6, 8) << " um\n"
              << "  mean radius       = " << num(m.mean_radius_m * 1e6, 8) << " um\n"
              << "  r^2-weight range  = " << num(support.breakpoints_m.front() * 1e6) << " - "
              << num(support.breakpoints_m.back() * 1e6) << " um (all but 1e-12)\n"
              << "  checks            : finite, positive number, water content and radii\n";
  }
}

// "advection, radiation, marshall-palmer:R, gunn-marshall:R" (size_distribution.hpp).
std::string preset_names() {
  std::string out;
  for (const auto& p : w::distribution_presets()) out += (out.empty() ? "" : ", ") + p.name;
  return out;
}

}  // namespace

void register_weather(CLI::App& app) {
  {
    auto* cmd = app.add_subcommand(
        "sigma", "extinction coefficient and Koschmieder visibility of weather conditions");
    auto conditions = std::make_shared<std::vector<std::string>>();
    auto opts = std::make_shared<CommonOptions>();
    auto json = std::make_shared<bool>(false);
    cmd->add_option("conditions", *conditions, "conditions, e.g. clear rain:8 fog:advection")->required();
    add_common(cmd, *opts, {});
    cmd->add_flag("--json", *json, "print JSON");
    cmd->callback([=] { run_sigma(*conditions, *opts, *json); });
  }
  {
    auto* cmd =
        app.add_subcommand("table", "optical quantities over wavelengths x conditions into a CSV, JSON or netCDF-4 file");
    auto t = std::make_shared<TableOptions>();
    auto opts = std::make_shared<CommonOptions>();
    cmd->add_option("--conditions", t->conditions, "comma-separated conditions; sweeps like rain:1..100")->required();
    cmd->add_option("--wavelengths", t->wavelengths, "START:STOP:STEPunit (400:800:10nm) or a list (550nm,10.6um)")
        ->capture_default_str();
    cmd->add_option("--quantities", t->quantities,
                    "comma-separated: " + w::quantity_names() +
                        ", moments:L (Legendre moments chi_0..chi_L of the phase function), phase (the bulk phase "
                        "function p at --angles, int p dOmega = 4 pi); all but sigma_ext need a Mie condition "
                        "(else empty)")
        ->capture_default_str();
    cmd->add_option("--angles", t->angles,
                    std::string("scattering angles of phase, degrees: START:STOP:STEP or A,B,... increasing, in "
                                "[0, 180] (default with phase: ") +
                        kDefaultTableAngles + "; only with phase in --quantities)");
    cmd->add_option("--format", t->format,
                    "csv, json, netcdf, libradtran (uvspec's wc_properties/ic_properties netCDF, one effective "
                    "radius per condition; needs moments:L) or disort (DTAUC SSALB PMOM per row; needs moments:L)")
        ->capture_default_str();
    cmd->add_option("--layer-thickness", t->layer_thickness,
                    "disort: the layer whose optical depth DTAUC = sigma_ext x thickness is written (m, km or mi)")
        ->capture_default_str();
    cmd->add_option("--out", t->out, "output file")->required();
    cmd->add_option("--threads", t->threads, "worker threads (0: all cores)")
        ->check(in_range(0, 1024))
        ->capture_default_str();
    add_common(cmd, *opts, {/*wavelength=*/false, /*tolerance=*/true});
    cmd->callback([=] { run_table(*t, *opts); });
  }
  {
    auto* cmd = app.add_subcommand("distribution", "moments and checks of a size distribution (a preset or a CSV file)");
    auto what = std::make_shared<std::string>();
    auto density = std::make_shared<std::string>("1000");
    auto json = std::make_shared<bool>(false);
    cmd->add_option("distribution", *what,
                    "a preset (" + preset_names() + ") or a CSV file (format: attenuvis help distribution-files)")
        ->required();
    cmd->add_option("--bulk-density", *density,
                    "kg/m^3 for the water content (ice: 917); " + w::range_text(w::domain::bulk_density))
        ->capture_default_str();
    cmd->add_flag("--json", *json, "print JSON");
    cmd->callback([=] { run_distribution(*what, *density, *json); });
  }
}

}  // namespace attenuvis::cli
