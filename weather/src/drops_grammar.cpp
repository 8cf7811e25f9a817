// Parametric drops in the condition grammar: drops:FAMILY:KEY=VALUE...[:OPTIONS]
// (condition_grammar.hpp lists the families; the distributions are built in
// sigma.cpp, condition_distribution).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "condition_fields.hpp"

namespace attenuvis::weather::detail {
namespace {

// drops:FAMILY:KEY=VALUE...[:OPTIONS]: the distribution's own parameters first
// (any order), then the Mie options; errors name the parameter and its field.

struct ParamValue {
  std::string text;
  std::size_t field = 0;
};
using Params = std::vector<std::pair<std::string, ParamValue>>;

// Reads KEY=VALUE fields from `from` on while KEY is one of `keys`; returns
// the index of the first field that is not (the options start there).
std::size_t read_params(const Fields& f, std::size_t from, std::initializer_list<const char*> keys, Params& out) {
  std::size_t i = from;
  for (; i < f.size(); ++i) {
    const auto eq = f[i].find('=');
    if (eq == std::string::npos) break;
    const std::string key = f[i].substr(0, eq);
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; })) break;
    for (const auto& [k, v] : out)
      if (k == key) f.fail("drops:" + f[1] + " parameter " + key + "= given twice (fields " +
                           std::to_string(v.field + 1) + " and " + std::to_string(i + 1) + ")");
    out.push_back({key, {f[i].substr(eq + 1), i}});
  }
  return i;
}

const ParamValue* find_param(const Params& p, const std::string& key) {
  for (const auto& [k, v] : p)
    if (k == key) return &v;
  return nullptr;
}

std::string where(const Fields& f, const std::string& key, const ParamValue& v) {
  return "drops:" + f[1] + " parameter " + key + "= (field " + std::to_string(v.field + 1) + ")";
}

// A number parameter, required, checked by `ok` (which says what it must be).
double number_param(const Fields& f, const Params& p, const std::string& key, bool (*ok)(double),
                    const char* must) {
  const ParamValue* v = find_param(p, key);
  if (!v) f.fail("drops:" + f[1] + " needs the parameter " + key + "=");
  double x = 0;
  try {
    x = io::parse_double(v->text, key);
  } catch (const std::invalid_argument& e) {
    f.fail(where(f, key, *v) + ": " + e.what());
  }
  if (!std::isfinite(x) || !ok(x)) f.fail(where(f, key, *v) + ": " + quote_text(v->text) + " must be " + must);
  return x;
}

// A radius with its unit (nm, um, mm or m: 5um, 0.2mm), in metres, within domain::drop_radius.
double radius_param(const Fields& f, const Params& p, const std::string& key) {
  const ParamValue* v = find_param(p, key);
  if (!v) f.fail("drops:" + f[1] + " needs the parameter " + key + "=RADIUS (with unit nm, um, mm or m)");
  std::string number = v->text, unit;
  while (!number.empty() && std::isalpha(static_cast<unsigned char>(number.back()))) {
    unit.insert(unit.begin(), number.back());
    number.pop_back();
  }
  // Divided by the (exact) power of ten, so that 5um is the double nearest 5e-6 m.
  const double per_m = unit == "nm" ? 1e9 : unit == "um" ? 1e6 : unit == "mm" ? 1e3 : unit == "m" ? 1.0 : 0.0;
  if (per_m == 0) f.fail(where(f, key, *v) + ": " + quote_text(v->text) + " needs a unit nm, um, mm or m");
  double r = 0;
  try {
    r = require_in_si(domain::drop_radius, io::parse_double(number, key) / per_m);
  } catch (const std::invalid_argument& e) {
    f.fail(where(f, key, *v) + ": " + e.what());
  }
  return r;
}

bool positive(double x) { return x > 0; }
bool above_one(double x) { return x > 1 && x <= 20; }
bool shape(double x) { return x > -1 && x <= 100; }  // alpha > -1: the number moment exists

Condition parametric(const Fields& f, ParametricDrops drops, std::size_t options_from) {
  MieCondition c = with_options(Drops{drops}, f, options_from);
  if (needs_amount(drops) && std::holds_alternative<AsGiven>(c.rescaling))
    f.fail("drops:" + f[1] + " needs its amount: :N=PER_CM3 or :lwc=G_PER_M3");
  return c;
}


}  // namespace

Condition parse_lognormal_drops(const Fields& f) {
  Params p;
  const std::size_t i = read_params(f, 2, {"r", "sg"}, p);
  const double r = radius_param(f, p, "r");
  const double sg = number_param(f, p, "sg", above_one, "in (1, 20]");
  return parametric(f, ParametricDrops{LogNormalDrops{r, sg}}, i);
}

Condition parse_gamma_drops(const Fields& f) {
  Params p;
  const std::size_t i = read_params(f, 2, {"r", "alpha"}, p);
  const double r = radius_param(f, p, "r");
  const double alpha = number_param(f, p, "alpha", [](double x) { return x > 0 && x <= 100; }, "in (0, 100]");
  return parametric(f, ParametricDrops{GammaDrops{r, alpha}}, i);
}

Condition parse_mgamma_drops(const Fields& f) {
  Params p;
  const std::size_t i = read_params(f, 2, {"a", "alpha", "b", "gamma", "rc"}, p);
  const double alpha = number_param(f, p, "alpha", shape, "in (-1, 100]");
  const double gamma =
      find_param(p, "gamma") ? number_param(f, p, "gamma", [](double x) { return x > 0 && x <= 10; }, "in (0, 10]")
                             : 1.0;
  if (find_param(p, "rc")) {
    if (find_param(p, "a") || find_param(p, "b")) f.fail("drops:mgamma takes rc= or a= and b=, not both");
    if (!(alpha > 0)) f.fail("drops:mgamma with rc= needs alpha > 0 (a mode at rc)");
    const double rc_um = radius_param(f, p, "rc") * 1e6;
    ModifiedGammaDrops g{1.0, alpha, alpha / (gamma * std::pow(rc_um, gamma)), gamma};
    MieCondition c = with_options(Drops{ParametricDrops{g}}, f, i);
    if (std::holds_alternative<AsGiven>(c.rescaling)) f.fail("drops:mgamma with rc= needs its amount: :N=PER_CM3 or :lwc=G_PER_M3");
    return c;
  }
  const double a = number_param(f, p, "a", positive, "> 0");
  const double b = number_param(f, p, "b", positive, "> 0");
  return parametric(f, ParametricDrops{ModifiedGammaDrops{a, alpha, b, gamma}}, i);
}

Condition parse_exponential_drops(const Fields& f) {
  Params p;
  const std::size_t i = read_params(f, 2, {"n0", "lambda"}, p);
  const double n0 = number_param(f, p, "n0", positive, "> 0");
  const double lambda = number_param(f, p, "lambda", positive, "> 0");
  return parametric(f, ParametricDrops{ExponentialDrops{n0, lambda}}, i);
}

Condition parse_powerlaw_drops(const Fields& f) {
  Params p;
  const std::size_t i = read_params(f, 2, {"nu", "rmin", "rmax"}, p);
  const double nu = number_param(f, p, "nu", [](double x) { return std::abs(x) <= 20; }, "in [-20, 20]");
  const double lo = radius_param(f, p, "rmin"), hi = radius_param(f, p, "rmax");
  if (!(hi > lo)) f.fail("drops:powerlaw needs rmin < rmax");
  return parametric(f, ParametricDrops{PowerLawDrops{nu, lo, hi}}, i);
}

std::string drops_text(const ParametricDrops& d) {
  using io::shortest;
  struct Visitor {
    std::string operator()(const LogNormalDrops& f) const {
      return "drops:lognormal:r=" + shortest(f.median_radius_m) + "m:sg=" + shortest(f.sigma_g);
    }
    std::string operator()(const GammaDrops& f) const {
      return "drops:gamma:r=" + shortest(f.mode_radius_m) + "m:alpha=" + shortest(f.alpha);
    }
    std::string operator()(const ModifiedGammaDrops& f) const {
      return "drops:mgamma:a=" + shortest(f.a) + ":alpha=" + shortest(f.alpha) + ":b=" + shortest(f.b) +
             ":gamma=" + shortest(f.gamma);
    }
    std::string operator()(const ExponentialDrops& f) const {
      return "drops:exponential:n0=" + shortest(f.n0_per_m3_per_mm) + ":lambda=" + shortest(f.lambda_per_mm);
    }
    std::string operator()(const PowerLawDrops& f) const {
      return "drops:powerlaw:nu=" + shortest(f.nu) + ":rmin=" + shortest(f.r_min_m) + "m:rmax=" +
             shortest(f.r_max_m) + "m";
    }
  };
  return std::visit(Visitor{}, d.family);
}

}  // namespace attenuvis::weather::detail
