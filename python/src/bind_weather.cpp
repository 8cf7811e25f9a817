// attenuvis._attenuvis.weather: the typed conditions (condition.hpp) as
// Python classes, one per C++ struct, with the variant Condition converted by
// pybind11 in both directions; sigma, bulk optics, sigma tables and size
// distributions.
//
// sigma, bulk optics and tables run through watched_call (watched_call.hpp):
// Ctrl-C sets Settings::cancel, the quadrature stops at its next panel and
// KeyboardInterrupt reaches Python.
//
// Bulk optics are returned as a dict of named fields (optics_fields below), so
// that a field added to BulkOptics needs one line here and none in the
// Python layer, which shows whatever the dict holds.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <string>
#include <vector>

#include "attenuvis/weather/bulk_optics.hpp"
#include "attenuvis/weather/condition.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "attenuvis/weather/sigma.hpp"
#include "attenuvis/weather/sigma_table.hpp"
#include "attenuvis/weather/size_distribution.hpp"
#include "bindings.hpp"
#include "watched_call.hpp"

namespace py = pybind11;
namespace w = attenuvis::weather;

namespace attenuvis::python {
namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::dict estimate(const w::IntegralEstimate& e) {
  py::dict d;
  d["value"] = e.value;
  d["error"] = e.error();
  d["quadrature_error"] = e.quadrature_error;
  d["tail_error"] = e.tail_error;
  d["asymptotic_error"] = e.asymptotic_error;
  d["resonance_error"] = e.resonance_error;
  d["rounding_error"] = e.rounding_error;
  return d;
}

// Every field of BulkOptics, by name (integrals as {value, error, parts}).
py::dict optics_fields(const w::BulkOptics& b) {
  py::dict d;
  d["extinction"] = estimate(b.extinction);
  d["scattering"] = estimate(b.scattering);
  d["absorption"] = estimate(b.absorption);
  d["albedo"] = py::make_tuple(b.albedo, b.albedo_error);
  d["asymmetry"] = py::make_tuple(b.asymmetry, b.asymmetry_error);
  d["evaluations"] = b.evaluations;
  d["floor_panels"] = b.floor_panels;
  d["max_size_parameter"] = b.max_size_parameter;
  d["scattering_computed"] = b.scattering_computed;
  d["method"] = b.method;
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
  return d;
}

void bind_conditions(py::module_& m) {
  py::enum_<w::RainLaw>(m, "RainLaw")
      .value("seed", w::RainLaw::seed)
      .value("carbonneau", w::RainLaw::carbonneau)
      .value("p1814", w::RainLaw::p1814);
  py::enum_<w::SnowType>(m, "SnowType").value("wet", w::SnowType::wet).value("dry", w::SnowType::dry);
  py::enum_<w::VisibilityFogModel>(m, "VisibilityFogModel")
      .value("kruse", w::VisibilityFogModel::kruse)
      .value("kim", w::VisibilityFogModel::kim)
      .value("naboulsi_advection", w::VisibilityFogModel::naboulsi_advection)
      .value("naboulsi_radiation", w::VisibilityFogModel::naboulsi_radiation);
  py::enum_<w::FogPreset>(m, "FogPreset")
      .value("advection", w::FogPreset::advection)
      .value("radiation", w::FogPreset::radiation);
  py::enum_<w::WaterTable>(m, "WaterTable")
      .value("hale_querry", w::WaterTable::hale_querry)
      .value("segelstein", w::WaterTable::segelstein)
      .value("ice", w::WaterTable::ice);

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
  py::class_<w::MarshallPalmerRain>(m, "MarshallPalmerRain")
      .def(py::init([](double r) { return w::MarshallPalmerRain{r}; }), py::arg("rate_mm_h"))
      .def_readwrite("rate_mm_h", &w::MarshallPalmerRain::rate_mm_h);
  py::class_<w::DistributionFile>(m, "DistributionFile")
      .def(py::init([](std::string p) { return w::DistributionFile{std::move(p)}; }), py::arg("path"))
      .def_readwrite("path", &w::DistributionFile::path);
  // Parametric drops (drops:FAMILY:...) travel as an opaque value; Python reads them as Fog.
  py::class_<w::ParametricDrops>(m, "ParametricDrops").def("__repr__", [](const w::ParametricDrops& d) {
    return w::to_text(w::MieCondition{d, w::SettingsWaterTable{}, w::AsGiven{}});
  });
  py::class_<w::SettingsWaterTable>(m, "SettingsWaterTable").def(py::init<>());
  py::class_<w::ConstantIndex>(m, "ConstantIndex")
      .def(py::init([](std::complex<double> c) { return w::ConstantIndex{c}; }), py::arg("m"))
      .def_readwrite("m", &w::ConstantIndex::m);
  py::class_<w::AsGiven>(m, "AsGiven").def(py::init<>());
  py::class_<w::NumberDensity>(m, "NumberDensity")
      .def(py::init([](double n) { return w::NumberDensity{n}; }), py::arg("per_cm3"))
      .def_readwrite("per_cm3", &w::NumberDensity::per_cm3);
  py::class_<w::LiquidWaterContent>(m, "LiquidWaterContent")
      .def(py::init([](double g) { return w::LiquidWaterContent{g}; }), py::arg("g_per_m3"))
      .def_readwrite("g_per_m3", &w::LiquidWaterContent::g_per_m3);
  py::class_<w::MieCondition>(m, "MieCondition")
      .def(py::init([](w::Drops d, w::IndexSource i, w::Rescaling r) { return w::MieCondition{d, i, r}; }),
           py::arg("drops"), py::arg("index"), py::arg("rescaling"))
      .def_readwrite("drops", &w::MieCondition::drops)
      .def_readwrite("index", &w::MieCondition::index)
      .def_readwrite("rescaling", &w::MieCondition::rescaling);

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

}  // namespace

void bind_weather(py::module_ module) {
  bind_conditions(module);
  bind_distributions(module);
  module.def(
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
  module.def(
      "condition_optics",
      [](const w::MieCondition& c, double wavelength_m, double rel_tolerance, const std::string& water_table) {
        w::Settings s;
        s.rel_tolerance = rel_tolerance;
        s.water_table = water_table;
        std::string source;
        const std::complex<double> m = w::condition_refractive_index(c, wavelength_m, s, &source);
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        py::dict d = optics_fields(watched_call([&] { return w::condition_bulk_optics(c, wavelength_m, s); }, cancel));
        d["m"] = m;
        d["index_source"] = source;
        return d;
      },
      py::arg("condition"), py::arg("wavelength_m"), py::arg("rel_tolerance"), py::arg("water_table"));
  module.def(
      "distribution_optics",
      [](const w::SizeDistribution& d, double wavelength_m, std::complex<double> m, double rel_tolerance) {
        w::QuadratureSettings q;
        q.rel_tolerance = rel_tolerance;
        std::atomic<bool> cancel{false};
        q.cancel = &cancel;
        py::dict out = optics_fields(watched_call([&] { return w::bulk_optics(d, wavelength_m, m, q); }, cancel));
        out["m"] = m;
        return out;
      },
      py::arg("distribution"), py::arg("wavelength_m"), py::arg("m"), py::arg("rel_tolerance"));
  module.def(
      "refractive_index",
      [](const std::string& table, double wavelength_m) { return w::refractive_index_table(table).at(wavelength_m); },
      py::arg("table"), py::arg("wavelength_m"));
  module.def("data_directory", &w::data_directory);
  module.def(
      "table",
      [](const std::vector<std::pair<std::string, w::Condition>>& conditions, const std::vector<double>& wavelengths,
         const std::string& convention, double contrast_threshold, double rel_tolerance,
         const std::string& water_table, int threads, const std::vector<double>& angles_deg) {
        std::vector<w::LabelledCondition> labelled;
        for (const auto& [label, c] : conditions) labelled.push_back({label, c});
        w::Settings s = settings(convention, contrast_threshold, rel_tolerance, water_table);
        std::atomic<bool> cancel{false};
        s.cancel = &cancel;
        const w::SigmaTable t = watched_call(
            [&] { return w::sigma_table(labelled, wavelengths, s, threads, {w::Quantity::sigma_ext}, -1, angles_deg); },
            cancel);
        const py::ssize_t W = static_cast<py::ssize_t>(wavelengths.size());
        const py::ssize_t C = static_cast<py::ssize_t>(labelled.size());
        const py::ssize_t A = static_cast<py::ssize_t>(angles_deg.size());
        py::array_t<double> value({C, W}), error({C, W});
        // The bulk phase function (int p dOmega = 4 pi) and its error; NaN where a cell has none.
        py::array_t<double> phase({C, W, A}), phase_error({C, W, A});
        std::vector<std::string> models(static_cast<std::size_t>(C));
        for (py::ssize_t c = 0; c < C; ++c)
          for (py::ssize_t wl = 0; wl < W; ++wl) {
            const w::TableCell& cell = t.at(static_cast<std::size_t>(wl), static_cast<std::size_t>(c));
            value.mutable_at(c, wl) = cell.sigma.per_m;
            error.mutable_at(c, wl) = cell.sigma.error_per_m;
            if (wl == 0) models[static_cast<std::size_t>(c)] = cell.sigma.model;
            for (py::ssize_t a = 0; a < A; ++a) {
              const w::QuantityValue p = w::table_phase(cell, static_cast<std::size_t>(a));
              phase.mutable_at(c, wl, a) = p.value;
              phase_error.mutable_at(c, wl, a) = p.error;
            }
          }
        return py::make_tuple(value, error, models, phase, phase_error);
      },
      py::arg("conditions"), py::arg("wavelengths_m"), py::arg("convention"), py::arg("contrast_threshold"),
      py::arg("rel_tolerance"), py::arg("water_table"), py::arg("threads"),
      py::arg("angles_deg") = std::vector<double>{});
}

}  // namespace attenuvis::python
