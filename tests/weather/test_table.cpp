// Tables of optical quantities: sweeps, the quantity registry, the rule for
// missing values, and the CSV layout (header first, parameters as numbers).
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <string>

#include "attenuvis/weather.hpp"
#include "attenuvis/weather/detail/sigma_table_formats.hpp"

using namespace attenuvis::weather;
using Catch::Matchers::Contains;

namespace {
std::vector<double> swept_values(const std::string& text) {
  std::vector<double> out;
  for (const auto& c : expand_conditions(text)) out.push_back(condition_parameter(c.condition)->value);
  return out;
}
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }
}  // namespace

TEST_CASE("a sweep A..B/STEP ends at B, on the grid or not", "[weather][table]") {
  // Off the grid: 1, 11, ..., 91, then B = 100 (the last step shorter).
  const auto rain = expand_conditions("rain:1..100/10");
  REQUIRE(rain.size() == 11);
  CHECK(rain.front().label == "rain:1");
  CHECK(rain[9].label == "rain:91");
  CHECK(rain.back().label == "rain:100");
  CHECK(condition_parameter(rain.back().condition)->value == 100.0);
  // On the grid with a decimal step: (4 - 0.5) / 0.1 = 34.99999999999999 in binary; B is still the
  // 36th value, once, and exactly 4 (within 1e-6 STEP of the grid point).
  const auto snow = swept_values("snow:dry:0.5..4/0.1");
  REQUIRE(snow.size() == 36);
  CHECK(snow.back() == 4.0);
  CHECK(snow[34] == Approx(3.9).epsilon(1e-12));
  CHECK(swept_values("fog:kim:200..1000/200m") == std::vector<double>{200, 400, 600, 800, 1000});
  CHECK(swept_values("rain:5..5") == std::vector<double>{5});
  CHECK(swept_values("rain:1..3") == std::vector<double>{1, 2, 3});
  // B just above a grid point by more than the tolerance is a value of its own.
  CHECK(swept_values("rain:1..3.001") == std::vector<double>{1, 2, 3, 3.001});
}

TEST_CASE("the quantity registry names every quantity once, with units and long names", "[weather][table]") {
  const auto& all = table_quantities();
  for (std::size_t i = 0; i < all.size(); ++i) {
    CHECK(static_cast<std::size_t>(all[i].id) == i);
    CHECK(!all[i].long_name.empty());
    for (std::size_t j = 0; j < i; ++j) CHECK(all[i].name != all[j].name);
    // CF's particle coefficients are named for aerosol, "suspended liquid or solid particles in air
    // (except cloud droplets)" (CF Standard Name Table, e.g. the description of
    // number_concentration_of_ambient_aerosol_particles_in_air): no quantity of fog or rain may claim them,
    // and a coefficient says why it has no standard name.
    CHECK(all[i].standard_name.find("aerosol") == std::string::npos);
    if (all[i].kind == QuantityKind::coefficient && all[i].standard_name.empty()) CHECK(!all[i].comment.empty());
  }
  CHECK(parse_quantity_list("g,sigma_ext,ssa") == std::vector<Quantity>{Quantity::g, Quantity::sigma_ext, Quantity::ssa});
  CHECK_THROWS_WITH(parse_quantity_list("sigma_ext,albedo"), Contains("unknown quantity 'albedo'") && Contains("ssa"));
  CHECK_THROWS_WITH(parse_quantity_list("g,g"), Contains("twice"));
  CHECK_THROWS(parse_quantity_list(""));
  CHECK(unit_text(QuantityKind::coefficient, SigmaUnit::per_km) == "1/km");
  CHECK(*udunits_text(QuantityKind::coefficient, SigmaUnit::per_km) == "km-1");
  CHECK(!udunits_text(QuantityKind::coefficient, SigmaUnit::dB_per_km));
}

TEST_CASE("table quantities: Mie rows obey energy conservation, other rows are missing", "[weather][table]") {
  const std::vector<LabelledCondition> conditions = {{"rain:8", parse_condition("rain:8")},
                                                     {"fog", parse_condition("fog:advection:m=1.33+0.01i")}};
  Settings s;
  const auto t = sigma_table(conditions, {550e-9}, s, 2, parse_quantity_list("sigma_ext,sigma_sca,sigma_abs,ssa,g"));
  const TableCell& rain = t.at(0, 0);
  CHECK(std::isfinite(table_value(rain, Quantity::sigma_ext).value));
  for (Quantity q : {Quantity::sigma_sca, Quantity::sigma_abs, Quantity::ssa, Quantity::g}) {
    CHECK(std::isnan(table_value(rain, q).value));
    CHECK(std::isnan(table_value(rain, q).error));
  }
  const TableCell& fog = t.at(0, 1);
  REQUIRE(fog.optics);
  const auto ext = table_value(fog, Quantity::sigma_ext), sca = table_value(fog, Quantity::sigma_sca),
             abs = table_value(fog, Quantity::sigma_abs), ssa = table_value(fog, Quantity::ssa),
             g = table_value(fog, Quantity::g);
  // sigma_ext (contour integral) = sigma_sca + sigma_abs (real-axis quadrature): Q_ext = Q_sca + Q_abs
  // for every sphere (Bohren & Huffman 1983, eq. 3.25), within the two computations' error estimates.
  CHECK(std::fabs(ext.value - (sca.value + abs.value)) <= ext.error + sca.error + abs.error);
  CHECK(std::fabs(ssa.value - sca.value / (sca.value + abs.value)) <= ssa.error);
  CHECK(ssa.value > 0.5);
  CHECK(ssa.value < 1.0);
  // Absorbing drops (k = 0.01) of ~10 um at 550 nm: strongly forward scattering, 0 < g < 1.
  CHECK(g.value > 0.7);
  CHECK(g.value < 1.0);
  CHECK(g.error < 1e-6);
  // sigma_ext alone asks for no real-axis optics (no Mie work beyond sigma()).
  const auto only_ext = sigma_table(conditions, {550e-9}, s, 2);
  CHECK(!only_ext.at(0, 1).optics);
}

TEST_CASE("CSV table: a plain header first, parameters as numeric columns, missing cells empty",
          "[weather][table]") {
  std::vector<LabelledCondition> conditions = expand_conditions("rain:1..3");
  for (const char* c : {"fog:kim:500m", "clear"}) conditions.push_back({c, parse_condition(c)});
  Settings s;
  const auto t = sigma_table(conditions, parse_wavelength_list("500:600:50nm"), s, 2,
                             parse_quantity_list("sigma_ext,ssa"));
  const std::string csv = detail::format_sigma_table_csv(t, SigmaUnit::per_km);
  CHECK(first_line(csv) ==
        "wavelength_nm,condition,rate_mm_h,visibility_m,sigma_ext_per_km,sigma_ext_error_per_km,ssa,ssa_error,"
        "koschmieder_visibility_m,convention");
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  // rain:1 at 500 nm: rate 1, no visibility, sigma in 1/km, power law error 0, no ssa for a power law.
  CHECK_THAT(line, Contains("500,rain:1,1,,"));
  CHECK_THAT(line, Contains(",0,,,"));
  int rows = 0;
  std::istringstream count(csv);
  while (std::getline(count, line)) ++rows;
  CHECK(rows == 1 + 3 * 5);  // header + 3 wavelengths (500, 550, 600: STOP on the grid) x 5 conditions
  CHECK(csv.find('#') == std::string::npos);
  const std::string sidecar = detail::format_sigma_table_sidecar(t, SigmaUnit::per_km, {"attenuvis test"});
  CHECK_THAT(sidecar, Contains("\"sigma_ext_per_km\"") && Contains("\"1/km\"") && Contains("missing_values") &&
                          Contains("attenuvis test"));
}

TEST_CASE("sigma's error parts add up to its error, on the contour and on the real axis", "[weather][table]") {
  const std::string file = std::string(ATTENUVIS_TEST_DATA_DIR) + "/weather/one_bin.csv";
  for (const std::string& text : {std::string("fog:advection"), "fog:file=" + file}) {
    INFO(text);
    const Sigma s = sigma(parse_condition(text), 550e-9, Settings{});
    REQUIRE(s.error_terms.size() >= 3);
    double sum = 0;
    for (const auto& e : s.error_terms) {
      CHECK(e.per_m >= 0);
      sum += e.per_m;
    }
    CHECK(sum == Approx(s.error_per_m).epsilon(1e-12));
    CHECK(s.note.find("1/m") == std::string::npos);  // the note carries no numbers in a unit
  }
}

TEST_CASE("table backscatter and lidar ratio: the bulk optics' values, per steradian, in the table's length unit",
          "[weather][table]") {
  // Radiation fog at 1.55 um: a few thousand Mie evaluations.
  std::vector<LabelledCondition> conditions = expand_conditions("fog:radiation");
  conditions.push_back(expand_conditions("rain:8").front());
  const double wavelength = 1550e-9;
  Settings s;
  const SigmaTable t = sigma_table(conditions, {wavelength}, s, 1,
                                   {Quantity::sigma_ext, Quantity::backscatter, Quantity::lidar_ratio});
  const auto& fog = std::get<MieCondition>(conditions[0].condition);
  const BulkOptics b = condition_optics(fog, wavelength, s, OpticsRequest{}).bulk;
  REQUIRE(b.backscatter_computed);
  const QuantityValue beta = table_value(t.at(0, 0), Quantity::backscatter);
  const QuantityValue ratio = table_value(t.at(0, 0), Quantity::lidar_ratio);
  CHECK(beta.value == b.backscatter.value);
  CHECK(beta.error == b.backscatter.error());
  CHECK(ratio.value == b.lidar_ratio);
  // S = sigma_ext / beta_pi, here with sigma_ext from the contour rule: the two agree within the errors.
  const QuantityValue ext = table_value(t.at(0, 0), Quantity::sigma_ext);
  CHECK(std::abs(ext.value / beta.value - ratio.value) <= ratio.error + ext.error / beta.value);
  // A power law has no drops: both missing.
  CHECK(std::isnan(table_value(t.at(0, 1), Quantity::backscatter).value));
  CHECK(std::isnan(table_value(t.at(0, 1), Quantity::lidar_ratio).value));
  // Units: per steradian, per m or per km; a dB/km table keeps the backscatter per km.
  CHECK(unit_text(info(Quantity::backscatter).kind, SigmaUnit::per_m) == "1/(m sr)");
  CHECK(unit_text(info(Quantity::backscatter).kind, SigmaUnit::dB_per_km) == "1/(km sr)");
  CHECK(in_table_unit(info(Quantity::backscatter).kind, 2e-4, SigmaUnit::per_km) == Approx(0.2).epsilon(1e-15));
  CHECK(unit_text(info(Quantity::lidar_ratio).kind, SigmaUnit::per_km) == "sr");
  CHECK(column_suffix(info(Quantity::lidar_ratio).kind, SigmaUnit::per_km) == "_sr");
}

TEST_CASE("table moments:L: chi_0..chi_L of Mie cells, the bulk optics' values, parsing", "[weather][table]") {
  const QuantityRequest r = parse_quantity_request("g,moments:3");
  CHECK(r.quantities == std::vector<Quantity>{Quantity::g});
  CHECK(r.max_moment == 3);
  CHECK(parse_quantity_request("moments:0").quantities.empty());
  CHECK(parse_quantity_request("sigma_ext").max_moment == -1);
  for (const char* bad : {"moments:", "moments:x", "moments:-1", "moments:1001", "moments:2,moments:3", "moments:2.5"})
    CHECK_THROWS_AS(parse_quantity_request(bad), std::invalid_argument);
  // Radiation fog at 10.6 um (strongly absorbing: a few hundred Mie evaluations) and a power law.
  std::vector<LabelledCondition> conditions = expand_conditions("fog:radiation");
  conditions.push_back(expand_conditions("rain:8").front());
  const Settings s;
  const SigmaTable t = sigma_table(conditions, {10.6e-6}, s, 1, {}, 3);
  OpticsRequest request;
  request.backscatter = false;
  request.legendre_moments = 3;
  const BulkOptics b = condition_optics(std::get<MieCondition>(conditions[0].condition), 10.6e-6, s, request).bulk;
  for (int l = 0; l <= 3; ++l) {
    CHECK(table_moment(t.at(0, 0), l).value == b.moments[l]);
    CHECK(table_moment(t.at(0, 0), l).error == b.moments_error[l]);
    CHECK(std::isnan(table_moment(t.at(0, 1), l).value));  // no drops: missing
  }
  CHECK(std::isnan(table_moment(t.at(0, 0), 4).value));  // beyond L
  const std::string csv = detail::format_sigma_table_csv(t, SigmaUnit::per_m);
  CHECK_THAT(first_line(csv), Contains(",chi_0,chi_0_error,chi_1,") && Contains(",chi_3_error,"));
}
