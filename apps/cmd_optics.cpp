// attenuvis optics: every bulk single-scattering quantity of Mie conditions
// with its error, units and method (argument parsing and printing only; the
// work is weather::condition_optics).
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "attenuvis/weather.hpp"
#include "command_help.hpp"
#include "commands.hpp"
#include "weather_options.hpp"

namespace attenuvis::cli {
namespace {

namespace w = attenuvis::weather;

std::string num(double v, int precision = 10) {
  std::ostringstream o;
  o.precision(precision);
  o << v;
  return o.str();
}

nlohmann::json estimate_json(const w::IntegralEstimate& e, const char* units) {
  return {{"value", e.value},
          {"error", e.error()},
          {"units", units},
          {"error_parts",
           {{"quadrature", e.quadrature_error},
            {"tails", e.tail_error},
            {"resonances", e.resonance_error},
            {"large_x_expansion", e.asymptotic_error}}}};
}

nlohmann::json optics_json(const std::string& label, const w::ConditionOptics& o) {
  const w::BulkOptics& b = o.bulk;
  nlohmann::json j = {{"condition", label},
                      {"wavelength_nm", o.wavelength_m * 1e9},
                      {"distribution", o.distribution},
                      {"refractive_index", o.index_source},
                      {"method", b.method},
                      {"tolerance_met", b.shortfall.empty()},
                      {"evaluations", b.evaluations},
                      {"sigma_ext", estimate_json(b.extinction, "1/m")}};
  if (!b.scattering_computed) {
    j["note"] = "only sigma_ext: the large-x expansion of Q_ext was used";
    return j;
  }
  j["sigma_sca"] = estimate_json(b.scattering, "1/m");
  j["sigma_abs"] = estimate_json(b.absorption, "1/m");
  j["ssa"] = {{"value", b.albedo}, {"error", b.albedo_error}, {"units", "1"}};
  j["g"] = {{"value", b.asymmetry}, {"error", b.asymmetry_error}, {"units", "1"}};
  if (b.backscatter_computed) {
    j["backscatter"] = estimate_json(b.backscatter, "1/(m sr)");
    j["lidar_ratio"] = {{"value", b.lidar_ratio}, {"error", b.lidar_ratio_error}, {"units", "sr"}};
  }
  if (!b.moments.empty())
    j["moments"] = {{"normalisation", "p(mu) = sum (2l+1) chi_l P_l(mu), chi_0 = 1, chi_1 = g; DISORT PMOM(l) = chi_l"},
                    {"values", b.moments},
                    {"errors", b.moments_error}};
  if (!b.expansion.alpha1.empty()) {
    const auto& v = b.expansion;
    const auto& e = b.expansion_error;
    j["expansion"] = {{"convention", "Mishchenko, Travis & Lacis 2002 sec. 4.11; alpha1_l = (2l+1) chi_l"},
                      {"alpha1", {{"values", v.alpha1}, {"errors", e.alpha1}}},
                      {"alpha2", {{"values", v.alpha2}, {"errors", e.alpha2}}},
                      {"alpha3", {{"values", v.alpha3}, {"errors", e.alpha3}}},
                      {"alpha4", {{"values", v.alpha4}, {"errors", e.alpha4}}},
                      {"beta1", {{"values", v.beta1}, {"errors", e.beta1}}},
                      {"beta2", {{"values", v.beta2}, {"errors", e.beta2}}}};
  }
  if (!b.phase.empty())
    j["phase_function"] = {{"normalisation", "int p dOmega = 4 pi (isotropic p = 1)"},
                           {"angles_deg", b.angles_deg},
                           {"values", b.phase},
                           {"errors", b.phase_error}};
  return j;
}

void print_text(const std::string& label, const w::ConditionOptics& o) {
  const w::BulkOptics& b = o.bulk;
  auto row = [](const char* name, double v, double e, const char* units) {
    std::cout << "  " << name << " = " << num(v) << " +- " << num(e, 3) << " " << units << "\n";
  };
  std::cout << label << " at " << num(o.wavelength_m * 1e9, 6) << " nm\n";
  row("sigma_ext  ", b.extinction.value, b.extinction.error(), "1/m");
  if (b.scattering_computed) {
    row("sigma_sca  ", b.scattering.value, b.scattering.error(), "1/m");
    row("sigma_abs  ", b.absorption.value, b.absorption.error(), "1/m");
    row("ssa        ", b.albedo, b.albedo_error, "");
    row("g          ", b.asymmetry, b.asymmetry_error, "");
    if (b.backscatter_computed) {
      row("backscatter", b.backscatter.value, b.backscatter.error(), "1/(m sr)");
      row("lidar ratio", b.lidar_ratio, b.lidar_ratio_error, "sr");
    }
    if (!b.moments.empty()) {
      std::cout << "  Legendre moments chi_l (p = sum (2l+1) chi_l P_l, chi_0 = 1; DISORT PMOM):\n";
      for (std::size_t l = 0; l < b.moments.size(); ++l)
        std::cout << "    " << l << "  " << num(b.moments[l], 12) << " +- " << num(b.moments_error[l], 3) << "\n";
    }
    if (!b.expansion.alpha1.empty()) {
      const auto& v = b.expansion;
      std::cout << "  scattering-matrix expansion (MTL 2002 sec. 4.11): l alpha1 alpha2 alpha3 alpha4 beta1 beta2\n";
      for (std::size_t l = 0; l < v.alpha1.size(); ++l)
        std::cout << "    " << l << "  " << num(v.alpha1[l], 8) << " " << num(v.alpha2[l], 8) << " "
                  << num(v.alpha3[l], 8) << " " << num(v.alpha4[l], 8) << " " << num(v.beta1[l], 8) << " "
                  << num(v.beta2[l], 8) << "\n";
    }
    if (!b.phase.empty()) {
      std::cout << "  phase function p(theta) (int p dOmega = 4 pi):\n";
      for (std::size_t i = 0; i < b.phase.size(); ++i)
        std::cout << "    " << num(b.angles_deg[i], 6) << " deg  " << num(b.phase[i]) << " +- "
                  << num(b.phase_error[i], 3) << "\n";
    }
  } else {
    std::cout << "  (only sigma_ext: the large-x expansion of Q_ext was used)\n";
  }
  std::cout << "  distribution: " << o.distribution << "\n  refractive index: " << o.index_source
            << "\n  method: " << b.method << "\n";
}

// One amplitude series per angle and drop: a bound that keeps a mistyped step from running for hours.
constexpr std::size_t kMaxOpticsAngles = 100000;

struct OpticsOptions {
  WeatherOptions weather;
  int moments = -1;
  std::string angles;
  bool polarised = false;
  bool json = false;
};

void run_optics(const std::vector<std::string>& conditions, const OpticsOptions& o) {
  const w::Settings s = weather_settings(o.weather);
  const double wavelength = wavelength_m(o.weather);
  w::OpticsRequest request;
  request.legendre_moments = o.moments;
  if (o.polarised && o.moments < 0) throw std::invalid_argument("--polarised needs --moments L");
  request.polarised = o.polarised;
  if (!o.angles.empty()) request.angles_deg = angle_list("--angles", o.angles, kMaxOpticsAngles);
  std::vector<std::pair<std::string, w::Condition>> parsed;  // all parse before any work
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    const w::Condition c = w::parse_condition(conditions[i]);
    if (!w::needs_mie(c))
      throw std::invalid_argument("condition " + std::to_string(i + 1) + " ('" + conditions[i] +
                                  "') has no particles: optics needs a Mie condition "
                                  "(fog:advection, fog:radiation, drops:..., ...) or an aerosol (haze:..., aerosol:...)");
    parsed.emplace_back(conditions[i], c);
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [label, c] : parsed) {
    const w::ConditionOptics r = w::condition_optics(c, wavelength, s, request);
    // A result that missed its tolerance (bulk_optics.hpp: nearly lossless
    // particles beyond the evaluation budget) is printed with the errors it
    // reached, and said so on stderr.
    if (!r.bulk.shortfall.empty()) std::cerr << "warning: " << label << ": " << r.bulk.shortfall << "\n";
    if (o.json) out.push_back(optics_json(label, r));
    else print_text(label, r);
  }
  if (o.json) std::cout << out.dump(2) << "\n";
}

}  // namespace

void register_optics(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "optics", "bulk single-scattering optics of drops and aerosols, each quantity with its error");
  auto conditions = std::make_shared<std::vector<std::string>>();
  auto opts = std::make_shared<OpticsOptions>();
  cmd->add_option("conditions", *conditions, "Mie conditions or aerosols, e.g. fog:advection haze:urban:rh=80")
      ->required();
  add_weather_options(cmd, opts->weather, {});
  cmd->add_option("--moments", opts->moments,
                  "Legendre moments chi_0..chi_L of the phase function (costs O(x^2) per drop)")
      ->check(in_range(0, 100000));
  cmd->add_option("--angles", opts->angles, "phase function at START:STOP:STEP or a list A,B,... (degrees)");
  cmd->add_flag("--polarised", opts->polarised,
                "with --moments: alpha1..alpha4, beta1, beta2 of the bulk scattering matrix");
  cmd->add_flag("--json", opts->json, "print JSON");
  cmd->callback([opts, conditions] { run_optics(*conditions, *opts); });
}

}  // namespace attenuvis::cli
