// attenuvis._attenuvis.weather: the typed conditions (condition.hpp) as
// Python classes, one per C++ struct, with the variant Condition converted by
// pybind11 in both directions; sigma, bulk optics, sigma tables and size
// distributions; the registries of names (registry.hpp).
//
// sigma, bulk optics and tables run through watched_call (watched_call.hpp):
// Ctrl-C sets Settings::cancel, the quadrature stops at its next panel and
// KeyboardInterrupt reaches Python.
//
// Names come from the C++ registries only: the enums are bound from them
// (a name's '-' becomes '_': naboulsi-advection is
// VisibilityFogModel.naboulsi_advection), and registry(kind) hands the Python
// layer every entry.  Bulk optics are returned as a dict built from
// BulkOptics' own field list (bulk_optics.hpp: for_each_field), so a field
// added there reaches Python with no change here or in the Python layer.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "attenuvis/weather/aerosol_optics.hpp"
#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/registry.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "attenuvis/weather/sigma_table.hpp"
#include "attenuvis/weather/size_distribution.hpp"
#include "bindings.hpp"
#include "watched_call.hpp"

namespace py = pybind11;
namespace w = attenuvis::weather;

namespace attenuvis::python {
namespace {

py::array_t<double> array(const std::vector<double>& v) { return py::array_t<double>(v.size(), v.data()); }

// An integral as {value, error, its parts}: error() and every field.
py::dict estimate(const w::IntegralEstimate& e) {
  py::dict d;
  d["value"] = e.value;
  d["error"] = e.error();
  w::for_each_field(e, [&](const char* name, double v) { d[name] = v; });
  return d;
}

// One BulkOptics field into the dict: integrals as estimate(), a value with
// its error as (value, error), the expansion as {alpha1: (values, errors), ...}.
struct OpticsField {
  py::dict& d;
  void operator()(const char* name, const w::IntegralEstimate& e) const { d[name] = estimate(e); }
  void operator()(const char* name, double value, double error) const { d[name] = py::make_tuple(value, error); }
  void operator()(const char* name, const std::vector<double>& values, const std::vector<double>& errors) const {
    d[name] = py::make_tuple(array(values), array(errors));
  }
  void operator()(const char* name, const std::vector<double>& values) const { d[name] = array(values); }
  void operator()(const char* name, const w::MatrixExpansion& values, const w::MatrixExpansion& errors) const {
    py::dict parts;
    w::for_each_field(values, errors, [&](const char* part, const std::vector<double>& v, const std::vector<double>& e) {
      parts[part] = py::make_tuple(array(v), array(e));
    });
    d[name] = parts;
  }
  template <class Scalar>  // counts, flags, the method text
  void operator()(const char* name, const Scalar& value) const {
    d[name] = value;
  }
};

// Every field of BulkOptics, by name.
py::dict optics_fields(const w::BulkOptics& b) {
  py::dict d;
  w::for_each_field(b, OpticsField{d});
  return d;
}

w::Settings settings(const std::string& convention, double contrast_threshold, double rel_tolerance,
                     const std::string& water_table) {
  w::Settings s;
  s.convention = w::parse_convention(convention);
  s.contrast_threshold = contrast_threshold;
  s.rel_tolerance = rel_tolerance;
  s.water_table = water_table;
  return s;
}

py::dict sigma_fields(const w::Sigma& s) {
  py::dict d;
  d["value"] = s.per_m;
  d["error"] = s.error_per_m;
  d["model"] = s.model;
  d["convention"] = s.convention;
  d["note"] = s.note;
  d["shortfall"] = s.shortfall;
  return d;
}

// A registry's name as a Python identifier: naboulsi-advection -> naboulsi_advection.
std::string identifier(std::string name) {
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// A Python enum with one value per row of a registry, named after the row.
template <class Enum, class Rows, class Member>
void bind_named_enum(py::module_& m, const char* name, const Rows& rows, Member id) {
  py::enum_<Enum> e(m, name);
  for (const auto& row : rows) e.value(identifier(row.name).c_str(), row.*id);
}

void bind_named_enums(py::module_& m) {
  bind_named_enum<w::RainLaw>(m, "RainLaw", w::rain_power_laws(), &w::RainLawCoefficients::law);
  bind_named_enum<w::SnowType>(m, "SnowType", w::snow_types(), &w::SnowTypeInfo::id);
  bind_named_enum<w::VisibilityFogModel>(m, "VisibilityFogModel", w::visibility_fog_models(),
                                         &w::VisibilityFogModelInfo::id);
  bind_named_enum<w::FogPreset>(m, "FogPreset", w::fog_presets(), &w::FogPresetInfo::id);
  bind_named_enum<w::WaterTable>(m, "WaterTable", w::water_tables(), &w::WaterTableInfo::id);
  bind_named_enum<w::AerosolComponent>(m, "AerosolComponent", w::aerosol_components(), &w::AerosolComponentInfo::id);
  bind_named_enum<w::AerosolMixture>(m, "AerosolMixture", w::aerosol_mixtures(), &w::AerosolMixtureInfo::id);
  bind_named_enum<w::HumidityRule>(m, "HumidityRule", w::humidity_rules(), &w::HumidityRuleInfo::id);
}

// The conditions set by a number and a model (no drops).
void bind_closed_form_conditions(py::module_& m) {
  py::class_<w::ClearAir>(m, "ClearAir")
      .def(py::init([](std::optional<double> v) { return w::ClearAir{v}; }), py::arg("visibility_m") = py::none())
      .def_readwrite("visibility_m", &w::ClearAir::visibility_m);
  py::class_<w::Visibility>(m, "Visibility")
      .def(py::init([](double v) { return w::Visibility{v}; }), py::arg("visibility_m"))
      .def_readwrite("visibility_m", &w::Visibility::visibility_m);
  py::class_<w::GivenSigma>(m, "GivenSigma")
      .def(py::init([](double s) { return w::GivenSigma{s}; }), py::arg("per_m"))
      .def_readwrite("per_m", &w::GivenSigma::per_m);
  py::class_<w::RainPowerLaw>(m, "RainPowerLaw")
      .def(py::init([](double r, w::RainLaw l) { return w::RainPowerLaw{r, l}; }), py::arg("rate_mm_h"),
           py::arg("law"))
      .def_readwrite("rate_mm_h", &w::RainPowerLaw::rate_mm_h)
      .def_readwrite("law", &w::RainPowerLaw::law);
  py::class_<w::Snow>(m, "Snow")
      .def(py::init([](w::SnowType t, double r) { return w::Snow{t, r}; }), py::arg("type"), py::arg("rate_mm_h"))
      .def_readwrite("type", &w::Snow::type)
      .def_readwrite("rate_mm_h", &w::Snow::rate_mm_h);
  py::class_<w::FogFromVisibility>(m, "FogFromVisibility")
      .def(py::init([](w::VisibilityFogModel mo, double v) { return w::FogFromVisibility{mo, v}; }),
           py::arg("model"), py::arg("visibility_m"))
      .def_readwrite("model", &w::FogFromVisibility::model)
      .def_readwrite("visibility_m", &w::FogFromVisibility::visibility_m);
}

// A Mie condition and its parts: the drops, the refractive index, the rescaling.
void bind_mie_condition(py::module_& m) {
  py::class_<w::MarshallPalmerRain>(m, "MarshallPalmerRain")
      .def(py::init([](double r) { return w::MarshallPalmerRain{r}; }), py::arg("rate_mm_h"))
      .def_readwrite("rate_mm_h", &w::MarshallPalmerRain::rate_mm_h);
  py::class_<w::DistributionFile>(m, "DistributionFile")
      .def(py::init([](std::string p) { return w::DistributionFile{std::move(p)}; }), py::arg("path"))
      .def_readwrite("path", &w::DistributionFile::path);
  // Parametric drops (drops:FAMILY:...) travel as an opaque value; Python reads them as Fog.
  py::class_<w::ParametricDrops>(m, "ParametricDrops").def("__repr__", [](const w::ParametricDrops& d) {
    return w::to_text(w::MieCondition{d, w::SettingsWaterTable{}, w::AsGiven{}, std::nullopt});
  });
  py::class_<w::SettingsWaterTable>(m, "SettingsWaterTable").def(py::init<>());
  py::class_<w::ConstantIndex>(m, "ConstantIndex")
      .def(py::init([](std::complex<double> c) { return w::ConstantIndex{c}; }), py::arg("m"))
      .def_readwrite("m", &w::ConstantIndex::m);
  py::class_<w::IndexFile>(m, "IndexFile")
      .def(py::init([](std::string p) { return w::IndexFile{std::move(p)}; }), py::arg("path"))
      .def_readwrite("path", &w::IndexFile::path);
  py::class_<w::AsGiven>(m, "AsGiven").def(py::init<>());
  py::class_<w::NumberDensity>(m, "NumberDensity")
      .def(py::init([](double n) { return w::NumberDensity{n}; }), py::arg("per_cm3"))
      .def_readwrite("per_cm3", &w::NumberDensity::per_cm3);
  py::class_<w::LiquidWaterContent>(m, "LiquidWaterContent")
      .def(py::init([](double g) { return w::LiquidWaterContent{g}; }), py::arg("g_per_m3"))
      .def_readwrite("g_per_m3", &w::LiquidWaterContent::g_per_m3);
  py::class_<w::MieCondition>(m, "MieCondition")
      .def(py::init([](w::Drops d, w::IndexSource i, w::Rescaling r) { return w::MieCondition{d, i, r, std::nullopt}; }),
           py::arg("drops"), py::arg("index"), py::arg("rescaling"))
      .def_readwrite("drops", &w::MieCondition::drops)
      .def_readwrite("index", &w::MieCondition::index)
      .def_readwrite("rescaling", &w::MieCondition::rescaling);
}

// An aerosol: an OPAC type or a user's mixture of components at a humidity, with its scaling.
void bind_aerosol_condition(py::module_& m) {
  py::class_<w::AerosolAmount>(m, "AerosolAmount")
      .def(py::init([](w::AerosolComponent c, double n) { return w::AerosolAmount{c, n}; }), py::arg("component"),
           py::arg("per_cm3"))
      .def_readwrite("component", &w::AerosolAmount::component)
      .def_readwrite("per_cm3", &w::AerosolAmount::per_cm3);
  py::class_<w::ScaledToVisibility>(m, "ScaledToVisibility")
      .def(py::init([](double v) { return w::ScaledToVisibility{v}; }), py::arg("visibility_m"))
      .def_readwrite("visibility_m", &w::ScaledToVisibility::visibility_m);
  py::class_<w::ScaledToDryMass>(m, "ScaledToDryMass")
      .def(py::init([](double v) { return w::ScaledToDryMass{v}; }), py::arg("ug_per_m3"))
      .def_readwrite("ug_per_m3", &w::ScaledToDryMass::ug_per_m3);
  py::class_<w::AerosolCondition>(m, "AerosolCondition")
      .def(py::init([](std::optional<w::AerosolMixture> mixture, std::vector<w::AerosolAmount> amounts, double rh,
                       w::HumidityRule rule, w::AerosolScaling scaling) {
             return w::AerosolCondition{mixture, std::move(amounts), rh, rule, scaling};
           }),
           py::arg("mixture"), py::arg("amounts"), py::arg("relative_humidity_percent"), py::arg("humidity_rule"),
           py::arg("scaling"))
      .def_readwrite("mixture", &w::AerosolCondition::mixture)
      .def_readwrite("amounts", &w::AerosolCondition::amounts)
      .def_readwrite("relative_humidity_percent", &w::AerosolCondition::relative_humidity_percent)
      .def_readwrite("humidity_rule", &w::AerosolCondition::humidity_rule)
      .def_readwrite("scaling", &w::AerosolCondition::scaling);
  m.def(
      "mixture_amounts", [](w::AerosolMixture mixture) { return w::info(mixture).amounts; }, py::arg("mixture"));
}

void bind_grammar(py::module_& m) {
  m.def("parse", &w::parse_condition, py::arg("text"));
  m.def(
      "expand",
      [](const std::string& text) {
        std::vector<std::pair<std::string, w::Condition>> out;
        for (auto& lc : w::expand_conditions(text)) out.emplace_back(lc.label, lc.condition);
        return out;
      },
      py::arg("text"));
  m.def("to_text", &w::to_text, py::arg("condition"));
  m.def("needs_mie", &w::needs_mie, py::arg("condition"));
  m.def("grammar", &w::condition_grammar);
}

void bind_conditions(py::module_& m) {
  bind_named_enums(m);
  bind_closed_form_conditions(m);
  bind_mie_condition(m);
  bind_aerosol_condition(m);
  bind_grammar(m);
}

// registry(kind): the entries as dicts {name, units, help, citation, and the kind's details}.
py::list registry_entries(const std::string& kind) {
  py::list out;
  for (const w::RegistryEntry& e : w::registry(kind)) {
    py::dict d;
    d["name"] = e.name;
    d["units"] = e.units;
    d["help"] = e.help;
    d["citation"] = e.citation;
    for (const auto& [key, value] : e.details) d[py::str(key)] = py::cast(value);
    out.append(d);
  }
  return out;
}

w::SizeDistribution distribution_from_arrays(const Doubles& radius_m, const Doubles& density_per_m4,
                                             const std::string& source) {
  if (radius_m.ndim() != 1 || radius_m.size() != density_per_m4.size() || radius_m.size() < 2)
    throw std::invalid_argument("radius and density: two 1-D arrays of the same length, at least 2 points");
  const double* r = radius_m.data();
  const double* n = density_per_m4.data();
  std::vector<w::TabulatedSegment> segments;
  for (py::ssize_t i = 0; i + 1 < radius_m.size(); ++i) {
    if (!(r[i] > 0) || !(r[i + 1] > r[i]))
      throw std::invalid_argument("radius[" + std::to_string(i + 1) + "]: radii must be positive and increase");
    if (!(n[i] >= 0) || !(n[i + 1] >= 0))
      throw std::invalid_argument("density[" + std::to_string(n[i] >= 0 ? i + 1 : i) +
                                  "]: densities must be finite and >= 0");
    segments.push_back({r[i], r[i + 1], n[i], n[i + 1]});
  }
  return w::SizeDistribution::tabulated(std::move(segments), source);
}

void bind_distributions(py::module_& m) {
  py::class_<w::SizeDistribution>(m, "SizeDistribution")
      .def_static("preset", &w::preset_distribution, py::arg("name"))
      .def_static("modified_gamma_um", &w::SizeDistribution::modified_gamma_um, py::arg("a"), py::arg("alpha"),
                  py::arg("b"), py::arg("gamma") = 1.0)
      .def_static("gamma", &w::SizeDistribution::gamma, py::arg("number_per_m3"), py::arg("alpha"),
                  py::arg("mode_radius_m"))
      .def_static("log_normal", &w::SizeDistribution::log_normal, py::arg("number_per_m3"),
                  py::arg("median_radius_m"), py::arg("sigma_g"))
      .def_static("exponential_diameter", &w::SizeDistribution::exponential_diameter, py::arg("n0_per_m3_per_mm"),
                  py::arg("lambda_per_mm"))
      .def_static("marshall_palmer", &w::SizeDistribution::marshall_palmer, py::arg("rain_rate_mm_h"))
      .def_static("gunn_marshall", &w::SizeDistribution::gunn_marshall, py::arg("rate_mm_h"))
      .def_static("power_law", &w::SizeDistribution::power_law, py::arg("c_si"), py::arg("nu"), py::arg("r_min_m"),
                  py::arg("r_max_m"))
      .def_static("from_arrays", &distribution_from_arrays, py::arg("radius_m"), py::arg("density_per_m4"),
                  py::arg("source"))
      .def("density",
           [](const w::SizeDistribution& d, const Doubles& r) {
             Doubles out(r.size());
             for (py::ssize_t i = 0; i < r.size(); ++i) out.mutable_data()[i] = d.density(r.data()[i]);
             return out;
           })
      .def("moment", &w::SizeDistribution::moment, py::arg("p"))
      .def("scaled", &w::SizeDistribution::scaled, py::arg("factor"))
      .def("normalised_to_number", [](const w::SizeDistribution& d, double n) { return w::normalised_to_number(d, n); })
      .def("normalised_to_water_content", [](const w::SizeDistribution& d, double kg, double rho) {
             return w::normalised_to_water_content(d, kg, rho);
           })
      .def("moments",
           [](const w::SizeDistribution& d, double rho) {
             const auto mo = w::moments(d, rho);
             py::dict out;
             out["number_per_m3"] = mo.number_per_m3;
             out["water_content_kg_m3"] = mo.water_content_kg_m3;
             out["effective_radius_m"] = mo.effective_radius_m;
             out["mode_radius_m"] = mo.mode_radius_m;
             out["mean_radius_m"] = mo.mean_radius_m;
             return out;
           })
      .def_property_readonly("name", &w::SizeDistribution::name)
      .def("describe", &w::SizeDistribution::describe);
}

// The cells of a table as arrays: per quantity (by its C++ name) the values
// and the errors over (conditions, wavelengths); the model of each
// condition; the bulk phase function (int p dOmega = 4 pi) and its error over
// (conditions, wavelengths, angles).  NaN where a cell has no such value.
py::tuple table_arrays(const w::SigmaTable& t) {
  const std::size_t W = t.wavelengths_m.size(), C = t.conditions.size(), A = t.angles_deg.size();
  const auto shape = [](std::size_t n) { return static_cast<py::ssize_t>(n); };
  py::dict values, errors;
  for (const w::Quantity q : t.quantities) {
    py::array_t<double> value({shape(C), shape(W)}), error({shape(C), shape(W)});
    for (std::size_t c = 0; c < C; ++c)
      for (std::size_t wl = 0; wl < W; ++wl) {
        const w::QuantityValue v = w::table_value(t.at(wl, c), q);
        value.mutable_at(c, wl) = v.value;
        error.mutable_at(c, wl) = v.error;
      }
    values[py::str(w::info(q).name)] = value;
    errors[py::str(w::info(q).name)] = error;
  }
  py::array_t<double> phase({shape(C), shape(W), shape(A)}), phase_error({shape(C), shape(W), shape(A)});
  std::vector<std::string> models(C);
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t wl = 0; wl < W; ++wl) {
      const w::TableCell& cell = t.at(wl, c);
      if (wl == 0) models[c] = cell.sigma.model;
      for (std::size_t a = 0; a < A; ++a) {
        const w::QuantityValue p = w::table_phase(cell, a);
        phase.mutable_at(c, wl, a) = p.value;
        phase_error.mutable_at(c, wl, a) = p.error;
      }
    }
  return py::make_tuple(values, errors, models, phase, phase_error);
}

void bind_sigma(py::module_& m) {
  m.def(
      "sigma",
      [](const w::Condition& c, double wavelength_m, const std::string& convention, double contrast_threshold,
         double rel_tolerance, const std::string& water_table) {
        w::Settings s = settings(convention, contrast_threshold, rel_tolerance, water_table);
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        return sigma_fields(watched_call([&] { return w::sigma(c, wavelength_m, s); }, cancel));
      },
      py::arg("condition"), py::arg("wavelength_m"), py::arg("convention"), py::arg("contrast_threshold"),
      py::arg("rel_tolerance"), py::arg("water_table"));
  m.def(
      "refractive_index",
      [](const std::string& table, double wavelength_m) { return w::refractive_index_table(table).at(wavelength_m); },
      py::arg("table"), py::arg("wavelength_m"));
  m.def("data_directory", &w::data_directory);
}

void bind_optics(py::module_& m) {
  m.def(
      "condition_optics",
      [](const w::MieCondition& c, double wavelength_m, double rel_tolerance, const std::string& water_table) {
        w::Settings s;
        s.rel_tolerance = rel_tolerance;
        s.water_table = water_table;
        std::string source;
        const std::complex<double> index = w::condition_refractive_index(c, wavelength_m, s, &source);
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        py::dict d = optics_fields(watched_call([&] { return w::condition_bulk_optics(c, wavelength_m, s); }, cancel));
        d["m"] = index;
        d["index_source"] = source;
        return d;
      },
      py::arg("condition"), py::arg("wavelength_m"), py::arg("rel_tolerance"), py::arg("water_table"));
  m.def(
      "aerosol_optics",
      [](const w::AerosolCondition& c, double wavelength_m, double rel_tolerance, double contrast_threshold) {
        w::Settings s;
        s.rel_tolerance = rel_tolerance;
        s.contrast_threshold = contrast_threshold;
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        const w::AerosolOptics o = watched_call(
            [&] { return w::aerosol_optics(c, wavelength_m, s, w::OpticsRequest{false, -1, {}, false}); }, cancel);
        py::dict d = optics_fields(o.bulk);
        d["index_source"] = o.index_source;
        d["model"] = o.model;
        d["number_scale"] = o.number_scale;
        return d;
      },
      py::arg("condition"), py::arg("wavelength_m"), py::arg("rel_tolerance"), py::arg("contrast_threshold"));
  m.def(
      "distribution_optics",
      [](const w::SizeDistribution& d, double wavelength_m, std::complex<double> index, double rel_tolerance) {
        w::QuadratureSettings q;
        q.rel_tolerance = rel_tolerance;
        std::atomic<bool> cancel{false};
        q.cancel = &cancel;
        py::dict out = optics_fields(watched_call([&] { return w::bulk_optics(d, wavelength_m, index, q); }, cancel));
        out["m"] = index;
        return out;
      },
      py::arg("distribution"), py::arg("wavelength_m"), py::arg("m"), py::arg("rel_tolerance"));
}

void bind_table(py::module_& m) {
  // The computed table itself, kept so that Python can write the formats the
  // C++ writers own (libRadtran's netCDF, DISORT's text) without recomputing.
  py::class_<w::SigmaTable, std::shared_ptr<w::SigmaTable>>(m, "SigmaTable")
      .def(
          "write",
          [](const w::SigmaTable& t, const std::string& path, const std::string& format, double layer_thickness_m,
             const std::string& producer) {
            w::TableWriteOptions options;
            options.layer_thickness_m = layer_thickness_m;
            py::gil_scoped_release release;
            w::write_sigma_table(t, path, w::parse_table_format(format), w::SigmaUnit::per_m, {producer}, options);
          },
          py::arg("path"), py::arg("format"), py::arg("layer_thickness_m"), py::arg("producer"));
  m.def(
      "table",
      [](const std::vector<std::pair<std::string, w::Condition>>& conditions, const std::vector<double>& wavelengths,
         const std::string& convention, double contrast_threshold, double rel_tolerance,
         const std::string& water_table, int threads, const std::vector<std::string>& quantities,
         const std::vector<double>& angles_deg, int max_moment) {
        std::vector<w::LabelledCondition> labelled;
        for (const auto& [label, c] : conditions) labelled.push_back({label, c});
        std::string names;
        for (const auto& q : quantities) names += (names.empty() ? "" : ",") + q;
        const std::vector<w::Quantity> asked = w::parse_quantity_list(names);
        w::Settings s = settings(convention, contrast_threshold, rel_tolerance, water_table);
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        auto table = std::make_shared<w::SigmaTable>(watched_call(
            [&] { return w::sigma_table(labelled, wavelengths, s, threads, asked, max_moment, angles_deg); },
            cancel));
        return py::make_tuple(table_arrays(*table), table);
      },
      py::arg("conditions"), py::arg("wavelengths_m"), py::arg("convention"), py::arg("contrast_threshold"),
      py::arg("rel_tolerance"), py::arg("water_table"), py::arg("threads"),
      py::arg("quantities") = std::vector<std::string>{"sigma_ext"}, py::arg("angles_deg") = std::vector<double>{},
      py::arg("max_moment") = -1);
}

}  // namespace

void bind_weather(py::module_ module) {
  bind_conditions(module);
  bind_distributions(module);
  bind_sigma(module);
  bind_optics(module);
  bind_table(module);
  module.def("registry", &registry_entries, py::arg("kind"));
  module.def("registry_kinds", &w::registry_kinds);
}

}  // namespace attenuvis::python
