// A sigma table as netCDF-4 laid out by the CF conventions 1.8
// (https://cfconventions.org/cf-conventions/v1.8/cf-conventions.html):
//
//   dimensions  wavelength, condition
//   wavelength(wavelength)       coordinate variable, nm, radiation_wavelength
//   condition_label(condition)   string auxiliary coordinate (the grammar text)
//   rate, visibility, given_sigma(condition)
//                                auxiliary coordinates: the parameter each
//                                condition is set by (the swept one); only
//                                the kinds present; _FillValue where a
//                                condition has none (CF 1.8 sec. 5)
//   Q(wavelength, condition)     every quantity asked for, with units,
//                                long_name, standard_name where CF has one
//                                that fits (table_quantity.cpp: none yet),
//                                coordinates and ancillary_variables = Q_error
//   Q_error(wavelength, condition)  its error estimate, same units
//   moment(moment)               coordinate: l = 0..L (only with moments:L)
//   chi(wavelength, condition, moment), chi_error   Legendre moments of the
//                                phase function (DISORT's PMOM), dimensionless
//   angle(angle)                 coordinate: scattering angle in degree (only
//                                with phase)
//   phase_function(wavelength, condition, angle), phase_function_error
//                                the bulk phase function, int p dOmega = 4 pi
//   koschmieder_visibility(wavelength, condition), model(condition),
//   sigma_ext_method(wavelength, condition)
//
// Missing values (missing_value_rule()) are NaN, declared as _FillValue.
// Written through io::NetcdfFile: staged and renamed, no partial file.
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "attenuvis/io/netcdf_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/detail/sigma_table_formats.hpp"
#include "attenuvis/weather/sigma_table.hpp"
#include "attenuvis/weather/visibility.hpp"

namespace attenuvis::weather {
namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

void describe(io::NetcdfFile& f, int var, const std::string& units, const std::string& long_name,
              const std::string& standard_name) {
  if (!units.empty()) f.set_attribute(var, "units", units);
  f.set_attribute(var, "long_name", long_name);
  if (!standard_name.empty()) f.set_attribute(var, "standard_name", standard_name);
}

void set_global_attributes(io::NetcdfFile& f, const SigmaTable& t, const TableProvenance& provenance) {
  const int g = io::NetcdfFile::global;
  f.set_attribute(g, "Conventions", "CF-1.8");
  f.set_attribute(g, "title", "Optical properties of weather conditions over wavelength (attenuvis sigma table)");
  f.set_attribute(g, "source", provenance.producer);
  f.set_attribute(g, "attenuvis_version", provenance.producer.substr(0, provenance.producer.find(';')));
  f.set_attribute(g, "unit_convention", to_string(t.settings.convention));
  f.set_attribute(g, "unit_convention_meaning",
                  "how ITU-R P.1817-1 rain and snow power laws are read: itu = dB/km as published, seed = as 1/km "
                  "(the seed paper); other conditions do not depend on it");
  const auto& table = refractive_index_table(t.settings.water_table);
  f.set_attribute(g, "refractive_index_source",
                  table.name() + ": " + table.citation() +
                      ", interpolated in ln(wavelength); a condition's :m= or :water= overrides it "
                      "(see sigma_ext_method)");
  f.set_attribute(g, "method",
                  "sigma_ext: Lorenz-Mie over the size distribution, contour integral above the real axis for "
                  "analytic distributions, else adaptive Gauss-Kronrod on the real axis (per cell in "
                  "sigma_ext_method); sigma_sca, sigma_abs, ssa, g, backscatter, lidar_ratio, chi, "
                  "phase_function: adaptive Gauss-Kronrod on the real axis; "
                  "closed-form models elsewhere (model)");
  f.set_attribute(g, "mie_rel_tolerance", t.settings.rel_tolerance);
  f.set_attribute(g, "contrast_threshold", t.settings.contrast_threshold);
  f.set_attribute(g, "missing_values", missing_value_rule());
}

// The auxiliary coordinates: the condition label and the parameter kinds present.
std::string define_condition_coordinates(io::NetcdfFile& f, const SigmaTable& t, int condition_dim, SigmaUnit unit,
                                         std::vector<std::pair<int, std::vector<double>>>& parameter_values) {
  std::string coordinates = "condition_label";
  for (ParameterKind kind : {ParameterKind::rate, ParameterKind::visibility, ParameterKind::given_sigma}) {
    std::vector<double> values(t.conditions.size(), kMissing);
    bool present = false;
    for (std::size_t c = 0; c < t.conditions.size(); ++c)
      if (const auto p = condition_parameter(t.conditions[c].condition); p && p->kind == kind) {
        values[c] = kind == ParameterKind::given_sigma ? convert_from_per_m(p->value, unit) : p->value;
        present = true;
      }
    if (!present) continue;
    const ParameterInfo& p = info(kind);
    const int var = f.add_double_variable(p.name, {condition_dim});
    f.set_attribute(var, "_FillValue", kMissing);
    describe(f, var, kind == ParameterKind::given_sigma ? *udunits_text(QuantityKind::coefficient, unit) : p.udunits,
             p.long_name, p.standard_name);
    parameter_values.push_back({var, values});
    coordinates += " " + p.name;
  }
  return coordinates;
}

// The (wavelength, condition) fields: every quantity and its error, and the
// Koschmieder visibility; their values in C order, written after enddef.
struct Field {
  int variable;
  std::vector<double> values;
};

std::vector<Field> define_fields(io::NetcdfFile& f, const SigmaTable& t, SigmaUnit unit, int wdim, int cdim,
                                 const std::string& coordinates) {
  std::vector<Field> fields;
  auto add = [&](const std::string& name, const std::string& units, const std::string& long_name,
                 const std::string& standard_name, const std::function<double(const TableCell&)>& value) {
    const int var = f.add_double_variable(name, {wdim, cdim});
    f.set_attribute(var, "_FillValue", kMissing);
    describe(f, var, units, long_name, standard_name);
    f.set_attribute(var, "coordinates", coordinates);
    std::vector<double> values(t.cells.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = value(t.cells[i]);
    fields.push_back({var, std::move(values)});
    return var;
  };
  for (Quantity q : t.quantities) {
    const QuantityInfo& qi = info(q);
    const QuantityKind kind = qi.kind;
    const std::string units = *udunits_text(kind, unit);
    const int var = add(qi.name, units, qi.long_name, qi.standard_name, [q, kind, unit](const TableCell& c) {
      return in_table_unit(kind, table_value(c, q).value, unit);
    });
    f.set_attribute(var, "ancillary_variables", qi.name + "_error");
    if (!qi.comment.empty()) f.set_attribute(var, "comment", qi.comment);
    const int err = add(qi.name + "_error", units, "error estimate of " + qi.name, "",
                        [q, kind, unit](const TableCell& c) { return in_table_unit(kind, table_value(c, q).error, unit); });
    f.set_attribute(err, "comment", "estimated bound on |" + qi.name + " - true value|; 0 for closed-form models");
  }
  const double threshold = t.settings.contrast_threshold;
  add("koschmieder_visibility", "m",
      "visibility from sigma_ext by Koschmieder at contrast threshold " + io::shortest(threshold),
      "visibility_in_air", [threshold](const TableCell& c) {
        return c.sigma.per_m > 0 ? koschmieder_visibility_m(c.sigma.per_m, threshold) : kMissing;
      });
  return fields;
}

// A (wavelength, condition, axis) field and its error companion, as the
// moments and the phase function are laid out; values in C order.
struct AxisField {
  int coordinate = -1, variable = -1, error_variable = -1;
  std::vector<double> axis, values, errors;
};

AxisField define_axis_field(io::NetcdfFile& f, const SigmaTable& t, int wdim, int cdim, const std::string& coordinates,
                            const std::string& dimension, const std::string& name, const std::string& long_name,
                            const std::vector<double>& axis,
                            const std::function<QuantityValue(const TableCell&, std::size_t)>& value) {
  AxisField out;
  out.axis = axis;
  const int dim = f.add_dimension(dimension, axis.size());
  out.coordinate = f.add_double_variable(dimension, {dim});
  out.variable = f.add_double_variable(name, {wdim, cdim, dim});
  f.set_attribute(out.variable, "_FillValue", kMissing);
  describe(f, out.variable, "1", long_name, "");
  f.set_attribute(out.variable, "coordinates", coordinates);
  f.set_attribute(out.variable, "ancillary_variables", name + "_error");
  out.error_variable = f.add_double_variable(name + "_error", {wdim, cdim, dim});
  f.set_attribute(out.error_variable, "_FillValue", kMissing);
  describe(f, out.error_variable, "1", "error estimate of " + name, "");
  for (const auto& cell : t.cells)
    for (std::size_t i = 0; i < axis.size(); ++i) {
      const QuantityValue v = value(cell, i);
      out.values.push_back(v.value);
      out.errors.push_back(v.error);
    }
  return out;
}

void write_axis_field(io::NetcdfFile& f, const AxisField& a) {
  f.write(a.coordinate, a.axis);
  f.write(a.variable, a.values);
  f.write(a.error_variable, a.errors);
}

// One string per condition (from the first wavelength's cell) or per cell.
std::vector<std::string> per_condition(const SigmaTable& t, const std::function<std::string(std::size_t c)>& text) {
  std::vector<std::string> out;
  for (std::size_t c = 0; c < t.conditions.size(); ++c) out.push_back(text(c));
  return out;
}

}  // namespace

void detail::write_sigma_table_netcdf(const SigmaTable& t, const std::string& path, SigmaUnit unit,
                              const TableProvenance& provenance) {
  if (!udunits_text(QuantityKind::coefficient, unit))
    throw std::invalid_argument("netCDF tables take --units m or km: " + to_string(unit) +
                                " has no UDUNITS spelling, which CF requires of a units attribute");
  if (t.wavelengths_m.empty() || t.conditions.empty()) throw std::invalid_argument("an empty table has no netCDF form");
  io::NetcdfFile f(path);
  set_global_attributes(f, t, provenance);
  const int wdim = f.add_dimension("wavelength", t.wavelengths_m.size());
  const int cdim = f.add_dimension("condition", t.conditions.size());
  const int wvar = f.add_double_variable("wavelength", {wdim});
  describe(f, wvar, "nm", "wavelength in vacuum", "radiation_wavelength");
  const int label_var = f.add_string_variable("condition_label", {cdim});
  describe(f, label_var, "", "condition as written in the attenuvis condition grammar", "");
  const int model_var = f.add_string_variable("model", {cdim});
  describe(f, model_var, "", "what sigma_ext is computed with, and its source", "");
  const int convention_var = f.add_string_variable("convention", {cdim});
  describe(f, convention_var, "", "power-law reading used (itu, seed; n/a where none enters)", "");
  std::vector<std::pair<int, std::vector<double>>> parameters;
  const std::string coordinates = define_condition_coordinates(f, t, cdim, unit, parameters);
  const std::vector<Field> fields = define_fields(f, t, unit, wdim, cdim, coordinates);
  // Legendre moments and the phase function, each on a dimension of its own.
  std::vector<AxisField> axis_fields;
  if (t.max_moment >= 0) {
    std::vector<double> orders;
    for (int l = 0; l <= t.max_moment; ++l) orders.push_back(static_cast<double>(l));
    axis_fields.push_back(define_axis_field(
        f, t, wdim, cdim, coordinates, "moment", "chi",
        "Legendre moments chi_l of the phase function, p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1, chi_1 = g "
        "(DISORT's PMOM)",
        orders, [](const TableCell& c, std::size_t l) { return table_moment(c, static_cast<int>(l)); }));
    describe(f, axis_fields.back().coordinate, "1", "order l of the Legendre moment", "");
  }
  if (!t.angles_deg.empty()) {
    axis_fields.push_back(define_axis_field(f, t, wdim, cdim, coordinates, "angle", "phase_function",
                                            "bulk phase function, scattering-weighted, normalised " +
                                                phase_function_normalisation(),
                                            t.angles_deg, table_phase));
    // No standard_name: the angle between incident and scattered directions is
    // named by units and long_name only, as the CF conventions allow, rather
    // than by a standard name this project cannot check against the table.
    describe(f, axis_fields.back().coordinate, "degree", "scattering angle", "");
  }
  const int method_var = f.add_string_variable("sigma_ext_method", {wdim, cdim});
  describe(f, method_var, "", "how sigma_ext was computed: refractive index, integration method, warnings (empty: closed form)", "");
  f.end_definitions();

  std::vector<double> wavelengths;
  for (double w : t.wavelengths_m) wavelengths.push_back(wavelength_nm(w));
  f.write(wvar, wavelengths);
  f.write(label_var, per_condition(t, [&](std::size_t c) { return t.conditions[c].label; }));
  f.write(model_var, per_condition(t, [&](std::size_t c) { return t.at(0, c).sigma.model; }));
  f.write(convention_var, per_condition(t, [&](std::size_t c) { return t.at(0, c).sigma.convention; }));
  std::vector<std::string> methods;
  for (const auto& cell : t.cells) methods.push_back(cell.sigma.note);
  f.write(method_var, methods);
  for (const auto& [var, values] : parameters) f.write(var, values);
  for (const auto& field : fields) f.write(field.variable, field.values);
  for (const auto& a : axis_fields) write_axis_field(f, a);
  f.commit();
}

}  // namespace attenuvis::weather
