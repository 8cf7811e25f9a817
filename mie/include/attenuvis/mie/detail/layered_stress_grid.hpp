// The stress grid on which layered_sphere() (attenuvis/mie/layered.hpp) is
// compared with its 50-digit referee, and the comparison of one case: the
// tests (tests/mie/test_layered_referee.cpp) run the cheap part, the report's
// Mie section (validation/src/section_mie_layered.cpp) all of it.
//
//   core x        1e-4, 1e-3, 1e-2, 0.1, 1, 10, 100, 1e3, 1e4
//   shell         thickness t = (r₁ − r₀)/r₀ in 1e-3, 1e-2, 0.1, 1, 10
//   indices       core × shell over 1.0001, 1.33 + 1e-8i, 1.5, 1.75 + 0.44i
//                 (soot), 3 + 0.1i, 10 + 10i
//   named cases   soot under sulphate (1.75 + 0.44i, 1.43 + 1e-8i), ice under
//                 water (1.31 + 2e-9i in 1.33 + 1e-9i, 0.55 µm), three and
//                 five layers, five thin alternating layers, layers within
//                 1e-5 of the medium's index, and a perfectly conducting core
//                 under one and under two shells, at the same core x.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "attenuvis/mie/layered.hpp"
#include "attenuvis/mie/layered_referee.hpp"

namespace attenuvis::mie::detail {

struct LayeredCase {
  std::string family;  // "two layers", "soot/sulphate", ...
  double core_x;       // the region: x of the core
  std::vector<double> x;
  std::vector<std::complex<double>> m;  // one per layer, or per shell on a conductor
  bool conducting_core = false;
};

inline const std::vector<double>& layered_grid_core_x() {
  static const std::vector<double> v = {1e-4, 1e-3, 1e-2, 0.1, 1, 10, 100, 1e3, 1e4};
  return v;
}

// The cases of one core x: every thickness and index pair, then the named
// cases.
inline std::vector<LayeredCase> layered_stress_cases(double x0) {
  using cd = std::complex<double>;
  const std::vector<double> thickness = {1e-3, 1e-2, 0.1, 1, 10};
  const std::vector<cd> index = {{1.0001, 0}, {1.33, 1e-8}, {1.5, 0}, {1.75, 0.44}, {3, 0.1}, {10, 10}};
  std::vector<LayeredCase> cases;
  for (double t : thickness)
    for (const cd& core : index)
      for (const cd& shell : index) cases.push_back({"two layers", x0, {x0, x0 * (1 + t)}, {core, shell}, false});
  const cd soot(1.75, 0.44), sulphate(1.43, 1e-8), ice(1.31, 2e-9), water(1.33, 1e-9);
  cases.push_back({"soot/sulphate", x0, {x0, 1.5 * x0}, {soot, sulphate}, false});
  cases.push_back({"soot/sulphate", x0, {x0, 3 * x0}, {soot, sulphate}, false});
  cases.push_back({"ice/water", x0, {x0, 1.2 * x0}, {ice, water}, false});
  cases.push_back({"ice/water", x0, {x0, 2 * x0}, {ice, water}, false});
  cases.push_back({"three layers", x0, {x0, 1.5 * x0, 2 * x0}, {soot, {1.5, 1e-3}, {1.33, 1e-8}}, false});
  cases.push_back({"five layers", x0, {x0, 1.1 * x0, 1.3 * x0, 1.6 * x0, 2 * x0},
                   {{10, 10}, {1.5, 0}, {3, 0.1}, {1.0001, 0}, {1.33, 1e-8}}, false});
  cases.push_back({"five layers", x0, {x0, 1.01 * x0, 1.02 * x0, 1.03 * x0, 1.04 * x0},
                   {{1.33, 0}, {1.5, 0.1}, {1.33, 0}, {1.5, 0.1}, {1.33, 0}}, false});
  cases.push_back({"index near 1", x0, {x0, 2 * x0}, {{1 + 1e-6, 0}, {1 + 1e-5, 1e-9}}, false});
  cases.push_back({"conducting core", x0, {x0, 1.3 * x0}, {{1.5, 0}}, true});
  cases.push_back({"conducting core", x0, {x0, 1.1 * x0, 2 * x0}, {{1.33, 1e-8}, {1.75, 0.44}}, true});
  return cases;
}

// A case against the referee: the largest of |q − q_ref| / max(|q_ref|,
// 1e-4 Qext_ref) over Qext, Qsca, Qabs, Qback and g (the measure of the
// homogeneous error map; required <= 1e-10), which quantity it is, and every
// quantity's values for messages.
struct LayeredCaseError {
  double error = 0;
  std::string quantity;
  std::string detail;  // "Qext got (ref ref); ..."
};

inline LayeredCaseError layered_case_error(const LayeredCase& c) {
  Efficiencies<double> d;
  Efficiencies<Referee> r;
  if (c.conducting_core) {
    d = layered_sphere(PerfectConductor{}, c.x, c.m);
    r = layered_sphere_referee(PerfectConductor{}, c.x, c.m);
  } else {
    d = layered_sphere(c.x, c.m);
    r = layered_sphere_referee(c.x, c.m);
  }
  const double qext = r.qext.convert_to<double>();
  const struct {
    const char* name;
    double got, ref;
  } qs[] = {{"Qext", d.qext, qext},
            {"Qsca", d.qsca, r.qsca.convert_to<double>()},
            {"Qabs", d.qabs, r.qabs.convert_to<double>()},
            {"Qback", d.qback, r.qback.convert_to<double>()},
            {"g", d.g, r.g.convert_to<double>()}};
  LayeredCaseError out;
  for (const auto& q : qs) {
    const double e =
        std::isfinite(q.got) ? std::abs(q.got - q.ref) / std::max(std::abs(q.ref), 1e-4 * std::abs(qext)) : INFINITY;
    out.detail += std::string(q.name) + " " + std::to_string(q.got) + " (ref " + std::to_string(q.ref) + "); ";
    if (!(e <= out.error)) out.error = e, out.quantity = q.name;
  }
  return out;
}

}  // namespace attenuvis::mie::detail
