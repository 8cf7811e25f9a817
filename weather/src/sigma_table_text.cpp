// The text formats of a sigma table: CSV (numbers only, one header line) with
// a JSON sidecar that says what every column is and how each cell was
// computed, and one self-contained JSON document holding both.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/detail/sigma_table_formats.hpp"
#include "attenuvis/weather/sigma_table.hpp"
#include "attenuvis/weather/visibility.hpp"

namespace attenuvis::weather {
namespace {

// One numeric column of the CSV (and member of a JSON row).
struct Column {
  std::string name, unit, long_name, standard_name, comment;
  std::function<double(std::size_t w, std::size_t c)> value;  // NaN: missing
};

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

// The phase function as one column per angle (CSV) or, for the JSON document,
// as per-row arrays over its "angle_deg" array (phase_columns false).
std::vector<Column> numeric_columns(const SigmaTable& t, SigmaUnit unit, bool phase_columns = true) {
  std::vector<Column> out;
  out.push_back({"wavelength_nm", "nm", "wavelength in vacuum", "radiation_wavelength", "",
                 [&t](std::size_t w, std::size_t) { return wavelength_nm(t.wavelengths_m[w]); }});
  // The parameters the conditions are set by (the swept ones among them), one column per kind present.
  for (ParameterKind kind : {ParameterKind::rate, ParameterKind::visibility, ParameterKind::given_sigma}) {
    const bool present = std::any_of(t.conditions.begin(), t.conditions.end(), [&](const LabelledCondition& c) {
      const auto p = condition_parameter(c.condition);
      return p && p->kind == kind;
    });
    if (!present) continue;
    const ParameterInfo& p = info(kind);
    const bool coefficient = kind == ParameterKind::given_sigma;
    const std::string u = coefficient ? to_string(unit) : p.unit;
    const std::string name = p.name + "_" + (coefficient ? unit_suffix(unit) : kind == ParameterKind::rate ? "mm_h" : "m");
    out.push_back({name, u, p.long_name, p.standard_name, "", [&t, kind, coefficient, unit](std::size_t, std::size_t c) {
                     const auto q = condition_parameter(t.conditions[c].condition);
                     if (!q || q->kind != kind) return kMissing;
                     return coefficient ? convert_from_per_m(q->value, unit) : q->value;
                   }});
  }
  for (Quantity q : t.quantities) {
    const QuantityInfo& qi = info(q);
    const std::string suffix = column_suffix(qi.kind, unit);
    const QuantityKind kind = qi.kind;
    out.push_back({qi.name + suffix, unit_text(kind, unit), qi.long_name, qi.standard_name, qi.comment,
                   [&t, q, kind, unit](std::size_t w, std::size_t c) {
                     return in_table_unit(kind, table_value(t.at(w, c), q).value, unit);
                   }});
    out.push_back({qi.name + "_error" + suffix, unit_text(kind, unit), "error estimate of " + qi.name, "", "",
                   [&t, q, kind, unit](std::size_t w, std::size_t c) {
                     return in_table_unit(kind, table_value(t.at(w, c), q).error, unit);
                   }});
  }
  for (int l = 0; l <= t.max_moment; ++l) {
    const std::string name = "chi_" + std::to_string(l);
    out.push_back({name, "1",
                   "Legendre moment " + std::to_string(l) +
                       " of the phase function, p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1 (DISORT's PMOM)",
                   "", "", [&t, l](std::size_t w, std::size_t c) { return table_moment(t.at(w, c), l).value; }});
    out.push_back({name + "_error", "1", "error estimate of " + name, "", "",
                   [&t, l](std::size_t w, std::size_t c) { return table_moment(t.at(w, c), l).error; }});
  }
  for (std::size_t i = 0; phase_columns && i < t.angles_deg.size(); ++i) {
    const std::string name = phase_column_name(t.angles_deg[i]);
    out.push_back({name, "1",
                   "bulk phase function at scattering angle " + io::shortest(t.angles_deg[i]) +
                       " deg, scattering-weighted, " + phase_function_normalisation(),
                   "", "", [&t, i](std::size_t w, std::size_t c) { return table_phase(t.at(w, c), i).value; }});
    out.push_back({name + "_error", "1", "error estimate of " + name, "", "",
                   [&t, i](std::size_t w, std::size_t c) { return table_phase(t.at(w, c), i).error; }});
  }
  const double threshold = t.settings.contrast_threshold;
  out.push_back({"koschmieder_visibility_m", "m",
                 "visibility from sigma_ext by Koschmieder at contrast threshold " + io::shortest(threshold),
                 "visibility_in_air", "", [&t, threshold](std::size_t w, std::size_t c) {
                   const double s = t.at(w, c).sigma.per_m;
                   return s > 0 ? koschmieder_visibility_m(s, threshold) : kMissing;
                 }});
  return out;
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char ch : s) o += (ch == '"') ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

// What the CSV's sidecar and the JSON document share: settings, columns, conditions, notes.
nlohmann::ordered_json metadata(const SigmaTable& t, SigmaUnit unit, const TableProvenance& provenance,
                        const std::vector<Column>& columns) {
  using json = nlohmann::ordered_json;
  json m;
  m["producer"] = provenance.producer;
  m["sigma_units"] = to_string(unit);
  m["convention"] = to_string(t.settings.convention);
  m["convention_applies_to"] = "ITU-R P.1817-1 rain and snow power laws (itu: dB/km as published; seed: read as 1/km)";
  m["contrast_threshold"] = t.settings.contrast_threshold;
  m["mie_rel_tolerance"] = t.settings.rel_tolerance;
  m["water_table"] = t.settings.water_table;
  m["missing_values"] = missing_value_rule();
  if (!t.angles_deg.empty())
    m["phase_function"] = {{"normalisation", phase_function_normalisation()},
                           {"weighting", "scattering-weighted: int p(theta; r) Q_sca pi r^2 n(r) dr / sigma_sca"},
                           {"angle_units", "degree"},
                           {"angle_deg", t.angles_deg}};
  json cols = json::array();
  cols.push_back({{"name", "condition"}, {"long_name", "condition as written in the condition grammar"}});
  for (const auto& c : columns) {
    json col = {{"name", c.name}, {"units", c.unit}, {"long_name", c.long_name}};
    if (!c.standard_name.empty()) col["standard_name"] = c.standard_name;
    if (!c.comment.empty()) col["comment"] = c.comment;
    cols.push_back(col);
  }
  cols.push_back({{"name", "convention"}, {"long_name", "power-law reading used for the row (n/a: none enters)"}});
  m["columns"] = cols;
  json conditions = json::array();
  for (std::size_t c = 0; c < t.conditions.size(); ++c)
    conditions.push_back({{"condition", t.conditions[c].label}, {"model", t.cells.empty() ? "" : t.at(0, c).sigma.model}});
  m["conditions"] = conditions;
  // How each cell was computed (refractive index, method, the parts of sigma_ext's error), where there is
  // more to say than the model: Mie cells and empirical models' warnings.
  json notes = json::array();
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      const TableCell& cell = t.at(w, c);
      if (cell.sigma.note.empty() && cell.sigma.error_terms.empty() && !cell.optics) continue;
      json n = {{"wavelength_nm", wavelength_nm(t.wavelengths_m[w])}, {"condition", t.conditions[c].label}};
      if (!cell.sigma.note.empty()) n["sigma_ext_method"] = cell.sigma.note;
      if (!cell.sigma.error_terms.empty()) {
        json terms = json::object();
        for (const auto& e : cell.sigma.error_terms) terms[e.name] = convert_from_per_m(e.per_m, unit);
        n["sigma_ext_error_terms_" + unit_suffix(unit)] = terms;
      }
      if (cell.optics) n["optics_method"] = cell.optics->method;
      notes.push_back(n);
    }
  m["notes"] = notes;
  return m;
}

}  // namespace

std::string detail::format_sigma_table_csv(const SigmaTable& t, SigmaUnit unit) {
  const auto columns = numeric_columns(t, unit);
  std::ostringstream o;
  // Header: the first line, plain names (csv.DictReader, pandas.read_csv read it as is).
  o << columns[0].name << ",condition";
  for (std::size_t i = 1; i < columns.size(); ++i) o << "," << columns[i].name;
  o << ",convention\n";
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      o << io::shortest(columns[0].value(w, c)) << "," << csv_quote(t.conditions[c].label);
      for (std::size_t i = 1; i < columns.size(); ++i) {
        const double v = columns[i].value(w, c);
        o << "," << (std::isfinite(v) ? io::shortest(v) : std::string());  // missing: empty cell
      }
      o << "," << t.at(w, c).sigma.convention << "\n";
    }
  return o.str();
}

std::string detail::format_sigma_table_sidecar(const SigmaTable& t, SigmaUnit unit, const TableProvenance& provenance) {
  nlohmann::ordered_json m = {{"describes", "the CSV table beside this file (same name without .meta.json)"}};
  m.update(metadata(t, unit, provenance, numeric_columns(t, unit)));
  return m.dump(2) + "\n";
}

std::string detail::format_sigma_table_json(const SigmaTable& t, SigmaUnit unit, const TableProvenance& provenance) {
  const auto columns = numeric_columns(t, unit, /*phase_columns=*/false);
  nlohmann::ordered_json doc = metadata(t, unit, provenance, columns);
  // The phase function: per row, arrays over the document's phase_function.angle_deg.
  const bool phase = !t.angles_deg.empty();
  if (phase) {
    auto& cols = doc["columns"];
    const auto convention = cols.back();  // keep "convention" last, as in the rows
    cols.erase(cols.size() - 1);
    cols.push_back({{"name", "phase"}, {"units", "1"}, {"dimension", "phase_function.angle_deg"},
                    {"long_name", "bulk phase function, scattering-weighted, " + phase_function_normalisation()}});
    cols.push_back({{"name", "phase_error"}, {"units", "1"}, {"dimension", "phase_function.angle_deg"},
                    {"long_name", "error estimate of phase"}});
    cols.push_back(convention);
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t w = 0; w < t.wavelengths_m.size(); ++w)
    for (std::size_t c = 0; c < t.conditions.size(); ++c) {
      nlohmann::ordered_json row = nlohmann::ordered_json::object();
      row["condition"] = t.conditions[c].label;
      for (const auto& col : columns) {
        const double v = col.value(w, c);
        row[col.name] = std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);  // missing: null
      }
      if (phase) {
        auto values = nlohmann::ordered_json::array(), errors = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < t.angles_deg.size(); ++i) {
          const QuantityValue p = table_phase(t.at(w, c), i);
          values.push_back(std::isfinite(p.value) ? nlohmann::ordered_json(p.value) : nlohmann::ordered_json(nullptr));
          errors.push_back(std::isfinite(p.error) ? nlohmann::ordered_json(p.error) : nlohmann::ordered_json(nullptr));
        }
        row["phase"] = values;
        row["phase_error"] = errors;
      }
      row["convention"] = t.at(w, c).sigma.convention;
      rows.push_back(row);
    }
  doc["rows"] = rows;
  return doc.dump(2) + "\n";
}

}  // namespace attenuvis::weather
