// The bulk phase function in sigma tables: the library's values at the
// table's angles, its normalisation, the CSV/JSON layout, and `attenuvis
// table --quantities ...,phase --angles` end to end, bad grids included.
#include <catch2/catch.hpp>

#include "../cli_run.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/legendre.hpp>
#include <nlohmann/json.hpp>

#include "attenuvis/weather.hpp"
#include "attenuvis/weather/detail/sigma_table_formats.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {

bool exists(const std::string& path) { return std::ifstream(path).good(); }

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

// Composite Simpson's rule on an even number of equal intervals of width h.
double simpson(const std::vector<double>& f, double h) {
  const std::size_t n = f.size() - 1;
  double sum = f.front() + f.back();
  for (std::size_t i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f[i];
  return sum * h / 3;
}

// (1/2) int_0^pi f(theta) sin(theta) dtheta from f on an equal grid over
// [0, 180] degrees, with every `stride`-th point.
double half_sphere_integral(const std::vector<double>& f, double step_deg, std::size_t stride) {
  const double deg = boost::math::constants::pi<double>() / 180;
  std::vector<double> g;
  for (std::size_t i = 0; i < f.size(); i += stride) g.push_back(0.5 * f[i] * std::sin(i * step_deg * deg));
  return simpson(g, stride * step_deg * deg);
}

}  // namespace

TEST_CASE("table phase: parsing of the request and of the angle grid", "[weather][table][phase]") {
  const QuantityRequest r = parse_quantity_request("g,phase,moments:2");
  CHECK(r.phase);
  CHECK(r.quantities == std::vector<Quantity>{Quantity::g});
  CHECK(r.max_moment == 2);
  CHECK(parse_quantity_request("phase").quantities.empty());
  CHECK(!parse_quantity_request("sigma_ext").phase);
  CHECK_THROWS_WITH(parse_quantity_request("phase,phase"), Contains("'phase' is listed twice"));
  CHECK_THROWS_WITH(parse_quantity_request("g,phse"), Contains("unknown quantity 'phse'") && Contains("lidar_ratio") &&
                                                          Contains("moments:L") && Contains("phase (the phase"));
  CHECK_NOTHROW(check_table_angles({0, 0.5, 90, 180}));
  CHECK_THROWS_WITH(check_table_angles({0, 181}), Contains("scattering angle 2 (181 deg) is outside [0, 180]"));
  CHECK_THROWS_WITH(check_table_angles({-1}), Contains("outside [0, 180]"));
  CHECK_THROWS_WITH(check_table_angles({90, 45}), Contains("scattering angle 2 (45 deg) does not increase"));
  CHECK_THROWS_WITH(check_table_angles({10, 10}), Contains("each listed once"));
  CHECK(phase_column_name(10) == "phase_10deg");
  CHECK(phase_column_name(0.5) == "phase_0.5deg");
  // A bad grid is refused before any cell is computed.
  const std::vector<LabelledCondition> fog = expand_conditions("fog:radiation");
  CHECK_THROWS_AS(sigma_table(fog, {10.6e-6}, Settings{}, 1, {}, -1, {0, 200}), std::invalid_argument);
}

TEST_CASE("table phase: the bulk optics' phase function and error at the table's angles, power laws missing",
          "[weather][table][phase]") {
  // Radiation fog at 10.6 um (strongly absorbing, x < ~15: a few hundred Mie evaluations) and a power law.
  std::vector<LabelledCondition> conditions = expand_conditions("fog:radiation");
  conditions.push_back(expand_conditions("rain:8").front());
  const std::vector<double> angles = {0, 30, 60, 90, 120, 150, 180};
  const Settings s;
  const SigmaTable t = sigma_table(conditions, {10.6e-6}, s, 1, {Quantity::sigma_ext}, -1, angles);
  OpticsRequest request;
  request.backscatter = false;  // as the table asks when backscatter and lidar_ratio are not among its quantities
  request.angles_deg = angles;
  const BulkOptics b = condition_optics(std::get<MieCondition>(conditions[0].condition), 10.6e-6, s, request).bulk;
  REQUIRE(b.phase.size() == angles.size());
  for (std::size_t i = 0; i < angles.size(); ++i) {
    CHECK(table_phase(t.at(0, 0), i).value == b.phase[i]);
    CHECK(table_phase(t.at(0, 0), i).error == b.phase_error[i]);
    CHECK(b.phase_error[i] > 0);
    CHECK(b.phase_error[i] < 1e-6 * b.phase[i]);
    CHECK(std::isnan(table_phase(t.at(0, 1), i).value));  // no drops: missing
    CHECK(std::isnan(table_phase(t.at(0, 1), i).error));
  }
  CHECK(std::isnan(table_phase(t.at(0, 0), angles.size()).value));  // beyond the grid
  CHECK(conditions_with_missing_values(t) == std::vector<std::string>{"rain:8"});

  // CSV: a plain header, two columns per angle in the style of the moments, values that read back exactly.
  const std::string csv = detail::format_sigma_table_csv(t, SigmaUnit::per_km);
  std::istringstream in(csv);
  std::string header, fog_row, rain_row;
  std::getline(in, header);
  std::getline(in, fog_row);
  std::getline(in, rain_row);
  CHECK_THAT(header, Contains(",sigma_ext_error_per_km,phase_0deg,phase_0deg_error,phase_30deg,") &&
                         Contains(",phase_180deg,phase_180deg_error,koschmieder_visibility_m,"));
  const auto names = split(header), fog = split(fog_row), rain = split(rain_row);
  REQUIRE(names.size() == fog.size());
  REQUIRE(names.size() == rain.size());
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const std::string name = phase_column_name(angles[i]);
    std::size_t col = 0;
    while (col < names.size() && names[col] != name) ++col;
    REQUIRE(col + 1 < names.size());
    CHECK(names[col + 1] == name + "_error");
    CHECK(std::stod(fog[col]) == b.phase[i]);
    CHECK(std::stod(fog[col + 1]) == b.phase_error[i]);
    CHECK(rain[col].empty());
  }
  // The sidecar and the JSON document name the normalisation and the angles.
  const std::string sidecar = detail::format_sigma_table_sidecar(t, SigmaUnit::per_km, {"attenuvis test"});
  CHECK_THAT(sidecar, Contains("\"phase_90deg_error\"") && Contains("int p dOmega = 4 pi"));
  const auto doc = nlohmann::json::parse(detail::format_sigma_table_json(t, SigmaUnit::per_km, {"attenuvis test"}));
  CHECK(doc["phase_function"]["angle_deg"].get<std::vector<double>>() == angles);
  CHECK_THAT(doc["phase_function"]["normalisation"].get<std::string>(), Contains("int p dOmega = 4 pi"));
  REQUIRE(doc["rows"][0]["phase"].size() == angles.size());
  CHECK(doc["rows"][0]["phase"][3].get<double>() == b.phase[3]);
  CHECK(doc["rows"][0]["phase_error"][3].get<double>() == b.phase_error[3]);
  CHECK(doc["rows"][1]["phase"][3].is_null());
  CHECK(!doc["rows"][0].contains("phase_90deg"));  // arrays, not a member per angle
}

TEST_CASE("table phase: (1/2) int p sin(theta) dtheta = 1 by Simpson's rule on a quarter-degree grid",
          "[weather][table][phase]") {
  // Radiation fog at 10.6 um: the drops' size parameters stay below ~15, so the phase function varies on
  // scales of several degrees and a 0.25-degree grid resolves it.  The normalisation int p dOmega = 4 pi
  // is then checked independently of the library: Simpson's rule on the grid (error estimated by the same
  // rule on every other point: |S_h - S_2h| is ~15x the error of S_h for a smooth integrand) plus the
  // library's own error of p carried through the same rule.
  const std::vector<LabelledCondition> fog = expand_conditions("fog:radiation");
  std::vector<double> angles;
  const double step = 0.25;
  for (int i = 0; i <= 720; ++i) angles.push_back(i * step);
  const SigmaTable t = sigma_table(fog, {10.6e-6}, Settings{}, 1, {}, -1, angles);
  std::vector<double> p, e;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    p.push_back(table_phase(t.at(0, 0), i).value);
    e.push_back(table_phase(t.at(0, 0), i).error);
  }
  const double fine = half_sphere_integral(p, step, 1), coarse = half_sphere_integral(p, step, 2);
  const double rule_error = std::abs(fine - coarse);
  const double value_error = half_sphere_integral(e, step, 1);
  INFO("S_h - 1 = " << fine - 1 << ", |S_h - S_2h| = " << rule_error << ", carried error of p = " << value_error);
  CHECK(rule_error < 1e-8);  // the grid resolves p: the check below is tight
  CHECK(std::abs(fine - 1) <= rule_error + value_error);
  // Forward peaked (p(0) > p(180)) and p(0) well above the isotropic p = 1.
  CHECK(p.front() > 2);
  CHECK(p.front() > p.back());
}

TEST_CASE("table phase: p(theta) = sum (2l+1) chi_l P_l(cos theta) with the table's own moments, at every angle",
          "[weather][table][phase]") {
  // Each drop's phase function is a polynomial of degree 2N in mu = cos theta with Legendre
  // coefficients (2l+1) chi_l (legendre_moments.hpp), so the bulk one is the same sum of the bulk
  // moments once L reaches 2N of the largest drop integrated.  Radiation fog at 10.6 um: x < 25
  // keeps 2N below ~110 (mie's series length, a little above Wiscombe's x + 4 x^(1/3) + 2).
  const std::vector<LabelledCondition> fog = expand_conditions("fog:radiation");
  const std::vector<double> angles = {0, 1, 5, 10, 30, 60, 90, 120, 150, 170, 179, 180};
  const int L = 150;
  const SigmaTable t = sigma_table(fog, {10.6e-6}, Settings{}, 1, {}, L, angles);
  REQUIRE(t.at(0, 0).optics);
  REQUIRE(t.at(0, 0).optics->max_size_parameter < 25);
  CHECK(std::abs(table_moment(t.at(0, 0), L).value) < 1e-300);  // the sum is complete: chi_L vanishes
  const double deg = boost::math::constants::pi<double>() / 180;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double mu = std::cos(angles[i] * deg);
    double sum = 0, sum_error = 0;
    for (int l = 0; l <= L; ++l) {
      const double pl = boost::math::legendre_p(l, mu);
      sum += (2 * l + 1) * table_moment(t.at(0, 0), l).value * pl;
      sum_error += (2 * l + 1) * table_moment(t.at(0, 0), l).error * std::abs(pl);
    }
    const QuantityValue p = table_phase(t.at(0, 0), i);
    INFO("theta = " << angles[i] << " deg: p = " << p.value << " +- " << p.error << ", sum = " << sum << " +- "
                    << sum_error);
    CHECK(std::abs(p.value - sum) <= p.error + sum_error);
    CHECK(std::abs(p.value - sum) < 1e-6 * p.value);  // the errors are small: the check is tight
  }
}

TEST_CASE("table --quantities ...,phase: the values of optics --angles, CSV and JSON agree",
          "[weather][cli][table][phase]") {
  const std::string csv = "weather_table_phase_test.csv", json = "weather_table_phase_test.json";
  for (const auto& f : {csv, csv + ".meta.json", json}) std::remove(f.c_str());
  // backscatter in the table as in optics (the same request to condition_optics: the same numbers).
  const std::string table = "table --conditions fog:radiation,rain:8 --wavelengths 1.55um --threads 2 "
                            "--quantities backscatter,phase --angles 0:180:45 ";
  const auto rc = cli_run::run(table + "--out " + csv);
  REQUIRE(rc.status == 0);
  CHECK_THAT(rc.output, Contains("the phase function at 5 angles"));
  const auto rj = cli_run::run(table + "--format json --out " + json);
  REQUIRE(rj.status == 0);
  const auto ro = cli_run::run("optics fog:radiation --wavelength 1.55um --angles 0:180:45 --json");
  REQUIRE(ro.status == 0);
  const auto optics = nlohmann::json::parse(ro.output)[0]["phase_function"];
  std::ifstream jin(json);
  const auto doc = nlohmann::json::parse(jin);
  const auto& row = doc["rows"][0];
  REQUIRE(row["condition"] == "fog:radiation");
  std::ifstream cin(csv);
  std::string header, line;
  std::getline(cin, header);
  std::getline(cin, line);
  const auto names = split(header), fog = split(line);
  REQUIRE(names.size() == fog.size());
  for (std::size_t i = 0; i < 5; ++i) {
    INFO("angle " << i * 45);
    CHECK(optics["angles_deg"][i].get<double>() == i * 45.0);
    CHECK(row["phase"][i].get<double>() == optics["values"][i].get<double>());
    CHECK(row["phase_error"][i].get<double>() == optics["errors"][i].get<double>());
    const std::string name = phase_column_name(i * 45.0);
    for (std::size_t col = 0; col < names.size(); ++col) {
      if (names[col] == name) CHECK(std::stod(fog[col]) == optics["values"][i].get<double>());
      if (names[col] == name + "_error") CHECK(std::stod(fog[col]) == optics["errors"][i].get<double>());
    }
  }
  CHECK(doc["rows"][1]["phase"][0].is_null());  // rain:8, a power law
  for (const auto& f : {csv, csv + ".meta.json", json}) std::remove(f.c_str());
}

TEST_CASE("table: phase without --angles takes every degree, bad angle grids are refused, no file left",
          "[weather][cli][table][phase]") {
  const std::string out = "weather_table_phase_default.csv";
  for (const auto& f : {out, out + ".meta.json"}) std::remove(f.c_str());
  const std::string base = "table --conditions fog:radiation --wavelengths 10.6um --out " + out + " ";
  const auto d = cli_run::run(base + "--quantities phase");
  REQUIRE(d.status == 0);
  CHECK_THAT(d.output, Contains("the phase function at 181 angles"));
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  CHECK_THAT(header, Contains(",phase_0deg,phase_0deg_error,phase_1deg,") && Contains(",phase_180deg_error,"));
  in.close();
  for (const auto& f : {out, out + ".meta.json"}) std::remove(f.c_str());

  struct Bad {
    const char* args;
    const char* message;
  };
  const Bad bad[] = {
      {"--quantities phase --angles 0:200:10", "--angles '0:200:10': scattering angles must lie in [0, 180]"},
      {"--quantities phase --angles 0:x:10", "--angles '0:x:10': cannot parse stop angle 'x'"},
      {"--quantities phase --angles 90,45", "scattering angle 2 (45 deg) does not increase"},
      {"--quantities phase --angles 0,10,10", "scattering angle 3 (10 deg) does not increase"},
      {"--quantities phase --angles 0:180:0.01", "gives 18001 angles, more than 10000"},
      {"--quantities phase --angles 10:0:1", "stop >= start"},
      {"--quantities sigma_ext --angles 0:180:10", "add phase to --quantities"},
      {"--quantities phase,phase", "'phase' is listed twice"},
  };
  for (const Bad& b : bad) {
    INFO(b.args);
    for (const char* format : {"csv", "netcdf"}) {
      const auto r = cli_run::run(base + b.args + " --format " + format);
      CHECK(r.status != 0);
      CHECK_THAT(r.output, Contains("attenuvis: error:") && Contains(b.message));
      CHECK(!exists(out));
      CHECK(!exists(out + ".meta.json"));
    }
  }
}
