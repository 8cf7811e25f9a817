// layered_sphere() against its 50-digit referee (attenuvis/mie/layered_referee.hpp:
// the same series in cpp_bin_float_50) on the stress grid of
// attenuvis/mie/detail/layered_stress_grid.hpp: core x 1e-4 ... 1e4, shells of
// 1e-3 ... 10 core radii, indices 1.0001 ... 10+10i, soot under sulphate, ice
// under water, three and five layers, a conducting core.
// Requirement (as for the homogeneous sphere, tests/mie/test_mie_referee.cpp):
// Qext, Qsca, Qabs, Qback and g within
//     |q - q_ref| <= max(1e-10 |q_ref|, 1e-14 Qext_ref)
// (layered_case_error() <= 1e-10), no NaN, no infinity, no exception.
//
// Cost (Release, one core of the development machine): core x <= 10, 1,140
// cases, ~2 s; core x = 100 ~5 s; core x = 1e3 (outer x up to 1.1e4) ~17 s and
// 1e4 (outer x up to 1.1e5, the long double path) ~400 s for its 190 cases.
// The normal run covers core x <= 10, [slow] adds core x = 100, a spread of
// core x = 1e3 and two cases at 1e4; the report (attenuvis reproduce, Mie
// section) runs the whole grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "attenuvis/mie/detail/layered_stress_grid.hpp"

namespace {

namespace mie = attenuvis::mie;
using mie::detail::LayeredCase;

std::string describe(const LayeredCase& c) {
  std::ostringstream os;
  os << std::setprecision(17) << c.family << ": x = {";
  for (double v : c.x) os << v << " ";
  os << "}, m = {";
  for (const auto& v : c.m) os << v.real() << "+" << v.imag() << "i ";
  os << "}" << (c.conducting_core ? " on a conducting core" : "");
  return os.str();
}

void check_cases(const std::vector<LayeredCase>& cases, const std::string& label) {
  double worst = 0;
  std::string where;
  for (const LayeredCase& c : cases) {
    INFO(describe(c));
    mie::detail::LayeredCaseError e;
    REQUIRE_NOTHROW(e = mie::detail::layered_case_error(c));
    INFO(e.detail);
    CHECK(e.error <= 1e-10);
    if (!(e.error <= worst)) worst = e.error, where = describe(c) + " (" + e.quantity + ")";
  }
  std::cout << "[layered referee] " << label << ": " << cases.size() << " cases, largest error " << worst
            << " (relative, floored at 1e-4 Qext) at " << where << "\n";
}

std::vector<LayeredCase> cases_at(const std::vector<double>& core_x) {
  std::vector<LayeredCase> all;
  for (double x0 : core_x) {
    const auto c = mie::detail::layered_stress_cases(x0);
    all.insert(all.end(), c.begin(), c.end());
  }
  return all;
}

}  // namespace

TEST_CASE("layered vs 50-digit referee: core x = 1e-4 ... 10, the whole grid", "[mie][layered][referee]") {
  check_cases(cases_at({1e-4, 1e-3, 1e-2, 0.1, 1, 10}), "core x = 1e-4 ... 10");
}

TEST_CASE("layered vs 50-digit referee: core x = 100, the whole grid", "[mie][layered][referee][slow]") {
  check_cases(cases_at({100}), "core x = 100");
}

TEST_CASE("layered vs 50-digit referee: core x = 1e3 (every 8th case) and 1e4 (two cases)",
          "[mie][layered][referee][slow]") {
  std::vector<LayeredCase> cases;
  const auto at_1e3 = mie::detail::layered_stress_cases(1e3);
  for (std::size_t i = 0; i < at_1e3.size(); i += 8) cases.push_back(at_1e3[i]);
  // Thin shells at core x = 1e4: outer x = 10010, the long double path.
  const auto at_1e4 = mie::detail::layered_stress_cases(1e4);
  for (const LayeredCase& c : at_1e4)
    if ((c.family == "soot/sulphate" && c.x[1] < 2e4) ||
        (c.family == "two layers" && c.x[1] < 1.002e4 && c.m[0] == c.m[1] && c.m[0] == std::complex<double>(1.33, 1e-8)))
      cases.push_back(c);
  check_cases(cases, "core x = 1e3 (sample), 1e4 (sample)");
}
