// The condition grammar (condition_grammar.hpp): one table of kinds, each
// with its keyword, grammar line, help text and parser; the help and every
// error message are generated from it.
#include "attenuvis/weather/condition_grammar.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/domains.hpp"
#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather {
namespace {

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("bad condition " + quote_text(text, 80) + ": " + why + "\n" + condition_grammar());
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// One value of a sweep A..B[/STEP][UNIT]: the field it replaces, the number
// (in the sweep's unit) and that unit.
struct SweptValue {
  std::size_t field = 0;
  double value = 0;
  std::string unit;
};

// The ':'-separated fields of one condition (fields[0] is the keyword) and
// the readers of its numbers.  A swept field yields its number directly.
class Fields {
 public:
  Fields(std::string text, std::vector<std::string> fields, std::optional<SweptValue> swept)
      : text_(std::move(text)), fields_(std::move(fields)), swept_(std::move(swept)) {}

  const std::string& text() const { return text_; }
  std::size_t size() const { return fields_.size(); }
  const std::string& operator[](std::size_t i) const { return fields_[i]; }
  [[noreturn]] void fail(const std::string& why) const { bad(text_, why); }
  void require(std::size_t n) const {
    if (fields_.size() < n) fail("missing field after '" + fields_.back() + "'");
  }
  void at_most(std::size_t n, const std::string& why) const {
    if (fields_.size() > n) fail(why);
  }
  bool swept_field_read() const { return !swept_ || swept_read_; }

  // Rate in mm/h within `range` (domains.hpp).
  double rate(std::size_t i, const Domain& range) const {
    try {
      if (const auto v = swept(i)) {
        if (!swept_->unit.empty()) fail("a rate is in mm/h and takes no unit ('" + swept_->unit + "')");
        return require_in(range, *v);
      }
      return read_in(range, fields_[i]);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  // A visibility in metres (units.hpp: parse_distance) within domain::visibility.
  double distance(std::size_t i) const {
    try {
      if (const auto v = swept(i)) {
        if (!(*v > 0)) throw std::invalid_argument("distance must be positive");
        return require_in_si(domain::visibility, *v * distance_unit_m(swept_->unit));
      }
      const double m = parse_distance(fields_[i]);
      if (!std::isfinite(m))  // 1e308km
        throw std::invalid_argument("visibility " + quote_text(fields_[i]) + " is outside its valid range " +
                                    range_text(domain::visibility));
      return require_in_si(domain::visibility, m);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  // sigma in 1/m, from VALUE[/m|/km|dB/km], within domain::sigma.
  double sigma(std::size_t i) const {
    if (const auto v = swept(i)) {
      if (!swept_->unit.empty()) fail("a swept sigma is in 1/m and takes no unit");
      return checked(domain::sigma, *v);
    }
    std::string v = fields_[i];
    SigmaUnit unit = SigmaUnit::per_m;
    for (auto [suffix, u] : {std::pair<const char*, SigmaUnit>{"dB/km", SigmaUnit::dB_per_km},
                             {"/km", SigmaUnit::per_km},
                             {"/m", SigmaUnit::per_m}}) {
      const std::string s = suffix;
      if (v.size() > s.size() && v.compare(v.size() - s.size(), s.size(), s) == 0) {
        unit = u;
        v = v.substr(0, v.size() - s.size());
        break;
      }
    }
    const double x = number(v, "sigma");
    if (x < 0) fail("sigma must be >= 0");
    return checked(domain::sigma, convert_to_per_m(x, unit));
  }
  // A number read and checked against `range`.
  double in(const Domain& range, const std::string& text) const {
    try {
      return read_in(range, text);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  double checked(const Domain& range, double value) const {
    try {
      return require_in(range, value);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }
  double number(const std::string& text, const std::string& what) const {
    try {
      return io::parse_double(text, what);
    } catch (const std::invalid_argument& e) {
      fail(e.what());
    }
  }

 private:
  double number(std::size_t i, const std::string& what) const { return number(fields_[i], what); }
  std::optional<double> swept(std::size_t i) const {
    if (!swept_ || swept_->field != i) return std::nullopt;
    swept_read_ = true;
    return swept_->value;
  }

  std::string text_;
  std::vector<std::string> fields_;
  std::optional<SweptValue> swept_;
  mutable bool swept_read_ = false;
};

// ---- Mie options ------------------------------------------------------------

// "1.33+1e-8i", "1.33,1e-8", "1.5" -> n + i k (io::split_index_text, the
// syntax of `attenuvis mie --m` too); k must be >= 0 (absorbing).
std::complex<double> parse_index(const std::string& text, const Fields& f) {
  io::IndexText parts;
  try {
    parts = io::split_index_text(text, "refractive index");
  } catch (const std::invalid_argument& e) {
    f.fail(e.what());
  }
  const double n = f.in(domain::index_real, parts.real);
  if (f.number(parts.imag, "refractive index imaginary part") < 0)
    f.fail("refractive index imaginary part must be >= 0 (absorbing; m = n + ik)");
  const double k = f.in(domain::index_imag, parts.imag);
  return {n, k};
}

struct MieOption {
  const char* key;  // "m=" ...
  const char* grammar;
  const char* help;
  void (*apply)(MieCondition& c, const std::string& value, const Fields& f);
};

void set_rescaling(MieCondition& c, Rescaling r, const Fields& f) {
  if (!std::holds_alternative<AsGiven>(c.rescaling) && c.rescaling.index() != r.index())
    f.fail("give N= or lwc=, not both");
  c.rescaling = r;
}

const MieOption kMieOptions[] = {
    {"m=", ":m=N+Ki | :m=N,K", "constant refractive index instead of the water table (m=1.33+0.001i or m=1.33,0.001)",
     [](MieCondition& c, const std::string& v, const Fields& f) { c.index = ConstantIndex{parse_index(v, f)}; }},
    {"water=", ":water=hale-querry|segelstein|ice",
     "refractive-index table (ice: Warren & Brandt 2008; default: the --water setting)",
     [](MieCondition& c, const std::string& v, const Fields& f) {
       if (v == "hale-querry" || v == "water") c.index = WaterTable::hale_querry;
       else if (v == "segelstein") c.index = WaterTable::segelstein;
       else if (v == "ice") c.index = WaterTable::ice;
       else f.fail("water table '" + v + "' is not hale-querry, segelstein or ice");
     }},
    {"N=", ":N=PER_CM3", "rescale the drops to this many particles per cm^3",
     [](MieCondition& c, const std::string& v, const Fields& f) {
       set_rescaling(c, NumberDensity{f.in(domain::number_density, v)}, f);
     }},
    {"lwc=", ":lwc=G_PER_M3", "rescale the drops to this liquid water content (g/m^3)",
     [](MieCondition& c, const std::string& v, const Fields& f) {
       set_rescaling(c, LiquidWaterContent{f.in(domain::water_content, v)}, f);
     }},
};

const MieOption* find_option(const std::string& field) {
  for (const auto& o : kMieOptions)
    if (field.rfind(o.key, 0) == 0) return &o;
  return nullptr;
}

MieCondition with_options(Drops drops, const Fields& f, std::size_t from) {
  MieCondition c{std::move(drops), SettingsWaterTable{}, AsGiven{}};
  for (std::size_t i = from; i < f.size(); ++i) {
    const MieOption* o = find_option(f[i]);
    if (!o) f.fail("unexpected field '" + f[i] + "'");
    o->apply(c, f[i].substr(std::string(o->key).size()), f);
  }
  return c;
}

// ---- Parametric drops ---------------------------------------------------------
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
  const double scale = unit == "nm" ? 1e-9 : unit == "um" ? 1e-6 : unit == "mm" ? 1e-3 : unit == "m" ? 1.0 : 0.0;
  if (scale == 0) f.fail(where(f, key, *v) + ": " + quote_text(v->text) + " needs a unit nm, um, mm or m");
  double r = 0;
  try {
    r = require_in_si(domain::drop_radius, io::parse_double(number, key) * scale);
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

bool family_is(const Fields& f, const char* name) { return f.size() >= 2 && f[1] == name; }

// ---- The kinds --------------------------------------------------------------

struct Kind {
  const char* keyword;
  const char* grammar;  // the grammar line
  const char* help;
  bool (*matches)(const Fields& f);  // among the kinds that share a keyword
  Condition (*parse)(const Fields& f);
};

bool always(const Fields&) { return true; }

bool is_empirical_fog(const std::string& name) {
  return name == "kruse" || name == "kim" || name == "naboulsi-advection" || name == "naboulsi-radiation";
}

const Kind kKinds[] = {
    {"clear", "clear | clear:DIST",
     "clear air: sigma = 0.00015 1/m (seed paper, Sec. Results), or Koschmieder from visibility DIST", always,
     [](const Fields& f) -> Condition {
       f.at_most(2, "clear takes at most a visibility");
       if (f.size() == 2) return ClearAir{f.distance(1)};
       return ClearAir{};
     }},
    {"visibility", "visibility:DIST", "any atmosphere of visibility DIST (Koschmieder), e.g. visibility:2km", always,
     [](const Fields& f) -> Condition {
       f.require(2);
       f.at_most(2, "visibility takes one distance");
       return Visibility{f.distance(1)};
     }},
    {"sigma", "sigma:VALUE[/m|/km|dB/km]", "a given sigma (default 1/m), e.g. sigma:0.002, sigma:3dB/km", always,
     [](const Fields& f) -> Condition {
       f.require(2);
       f.at_most(2, "sigma takes one value");
       return GivenSigma{f.sigma(1)};
     }},
    {"rain", "rain:RATE:mie[:OPTIONS]", "Mie over Marshall-Palmer drops, RATE mm/h, e.g. rain:8:mie",
     [](const Fields& f) { return f.size() >= 3 && f[2] == "mie"; },
     [](const Fields& f) -> Condition { return with_options(MarshallPalmerRain{f.rate(1, domain::rain_rate)}, f, 3); }},
    {"rain", "rain:RATE[:seed|carbonneau|p1814]",
     "power law, RATE mm/h, read per --convention; seed (default): k=1.17, alpha=0.65; e.g. rain:8", always,
     [](const Fields& f) -> Condition {
       f.require(2);
       const double rate = f.rate(1, domain::rain_rate);
       if (f.size() < 3) return RainPowerLaw{rate, RainLaw::seed};
       f.at_most(3, "options (m=, N=...) apply only to rain:RATE:mie");
       try {
         return RainPowerLaw{rate, rain_power_law(f[2]).law};
       } catch (const std::invalid_argument&) {
         std::string names;
         for (const auto& l : rain_power_laws()) names += l.name + ", ";
         f.fail("unknown rain model '" + f[2] + "' (" + names + "or mie)");
       }
     }},
    {"snow", "snow:wet:RATE | snow:dry:RATE", "P.1817-1 a(lambda) S^b, RATE mm/h, read per --convention", always,
     [](const Fields& f) -> Condition {
       f.require(3);
       SnowType type = SnowType::dry;
       if (f[1] == "wet") type = SnowType::wet;
       else if (f[1] != "dry") f.fail("snow type must be wet or dry");
       f.at_most(3, "snow takes a type and a rate");
       return Snow{type, f.rate(2, domain::snow_rate)};
     }},
    {"fog", "fog:advection | fog:radiation | fog:file=PATH  [:OPTIONS]",
     "Mie over the P.1817-1 / seed modified-gamma presets or a size-distribution CSV",
     [](const Fields& f) {
       return f.size() >= 2 && (f[1] == "advection" || f[1] == "radiation" || f[1].rfind("file=", 0) == 0);
     },
     [](const Fields& f) -> Condition {
       if (f[1] == "advection") return with_options(FogPreset::advection, f, 2);
       if (f[1] == "radiation") return with_options(FogPreset::radiation, f, 2);
       // A path may itself contain ':'; it runs up to the first option field.
       std::string path = f[1].substr(5);
       std::size_t i = 2;
       while (i < f.size() && !find_option(f[i])) path += ":" + f[i++];
       if (path.empty()) f.fail("fog:file= needs a path");
       return with_options(DistributionFile{path}, f, i);
     }},
    {"drops", "drops:lognormal:r=RADIUS:sg=SG  [:OPTIONS]",
     "Mie over a log-normal: median radius, geometric std. dev. SG in (1, 20]; needs N= or lwc=",
     [](const Fields& f) { return family_is(f, "lognormal"); },
     [](const Fields& f) -> Condition {
       Params p;
       const std::size_t i = read_params(f, 2, {"r", "sg"}, p);
       const double r = radius_param(f, p, "r");
       const double sg = number_param(f, p, "sg", above_one, "in (1, 20]");
       return parametric(f, ParametricDrops{LogNormalDrops{r, sg}}, i);
     }},
    {"drops", "drops:gamma:r=RADIUS:alpha=A  [:OPTIONS]",
     "Mie over a gamma n ~ r^A exp(-A r/RADIUS): mode radius, shape A in (-1, 100]; needs N= or lwc=",
     [](const Fields& f) { return family_is(f, "gamma"); },
     [](const Fields& f) -> Condition {
       Params p;
       const std::size_t i = read_params(f, 2, {"r", "alpha"}, p);
       const double r = radius_param(f, p, "r");
       const double alpha = number_param(f, p, "alpha", [](double x) { return x > 0 && x <= 100; }, "in (0, 100]");
       return parametric(f, ParametricDrops{GammaDrops{r, alpha}}, i);
     }},
    {"drops", "drops:mgamma:a=A:alpha=AL:b=B[:gamma=G] | drops:mgamma:rc=RADIUS:alpha=AL[:gamma=G]",
     "Mie over Deirmendjian's n = A r^AL exp(-B r^G), r in um, n in cm^-3 um^-1 (G = 1 by default); "
     "with rc= (mode radius, B = AL/(G rc^G)) it needs N= or lwc=",
     [](const Fields& f) { return family_is(f, "mgamma"); },
     [](const Fields& f) -> Condition {
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
     }},
    {"drops", "drops:exponential:n0=N0:lambda=L  [:OPTIONS]",
     "Mie over N(D) = N0 exp(-L D) in diameter D: N0 in m^-3 mm^-1, L in mm^-1 (Marshall & Palmer form)",
     [](const Fields& f) { return family_is(f, "exponential"); },
     [](const Fields& f) -> Condition {
       Params p;
       const std::size_t i = read_params(f, 2, {"n0", "lambda"}, p);
       const double n0 = number_param(f, p, "n0", positive, "> 0");
       const double lambda = number_param(f, p, "lambda", positive, "> 0");
       return parametric(f, ParametricDrops{ExponentialDrops{n0, lambda}}, i);
     }},
    {"drops", "drops:powerlaw:nu=NU:rmin=RADIUS:rmax=RADIUS  [:OPTIONS]",
     "Mie over a Junge power law n ~ r^-NU on [rmin, rmax]; needs N= or lwc=",
     [](const Fields& f) { return family_is(f, "powerlaw"); },
     [](const Fields& f) -> Condition {
       Params p;
       const std::size_t i = read_params(f, 2, {"nu", "rmin", "rmax"}, p);
       const double nu = number_param(f, p, "nu", [](double x) { return std::abs(x) <= 20; }, "in [-20, 20]");
       const double lo = radius_param(f, p, "rmin"), hi = radius_param(f, p, "rmax");
       if (!(hi > lo)) f.fail("drops:powerlaw needs rmin < rmax");
       return parametric(f, ParametricDrops{PowerLawDrops{nu, lo, hi}}, i);
     }},
    {"fog", "fog:kruse|kim|naboulsi-advection|naboulsi-radiation:DIST", "empirical fog from visibility DIST",
     [](const Fields& f) { return f.size() >= 2 && is_empirical_fog(f[1]); },
     [](const Fields& f) -> Condition {
       f.require(3);
       f.at_most(3, "empirical fog takes one visibility");
       const VisibilityFogModel model = f[1] == "kruse"                ? VisibilityFogModel::kruse
                                        : f[1] == "kim"                ? VisibilityFogModel::kim
                                        : f[1] == "naboulsi-advection" ? VisibilityFogModel::naboulsi_advection
                                                                       : VisibilityFogModel::naboulsi_radiation;
       return FogFromVisibility{model, f.distance(2)};
     }},
};

std::string generate_grammar() {
  std::size_t width = 0;
  for (const auto& k : kKinds) width = std::max(width, std::string(k.grammar).size());
  for (const auto& o : kMieOptions) width = std::max(width, std::string(o.grammar).size() + 2);
  std::ostringstream out;
  const auto line = [&](const std::string& left, const std::string& right) {
    out << "  " << left << std::string(width + 2 - left.size(), ' ') << right << "\n";
  };
  out << "conditions:\n";
  for (const auto& k : kKinds) line(k.grammar, k.help);
  out << "  OPTIONS after a Mie condition (fog:..., rain:RATE:mie, drops:...), any order:\n";
  for (const auto& o : kMieOptions) line(std::string("  ") + o.grammar, o.help);
  out << "  RATE in mm/h; DIST a number with unit " << distance_units() << " (bare number: m), e.g. 500m, 2km\n"
      << "  in tables a RATE, DIST or VALUE may sweep: A..B or A..B/STEP (rain:1..100, fog:kim:200..1000/200m)\n"
      << "  valid ranges: rain RATE " << range_text(domain::rain_rate) << ", snow RATE "
      << range_text(domain::snow_rate) << ", DIST " << range_text(domain::visibility) << ",\n"
      << "    sigma VALUE " << range_text(domain::sigma) << " (in any unit), N= " << range_text(domain::number_density)
      << ", lwc= " << range_text(domain::water_content) << ",\n"
      << "    m= n " << range_text(domain::index_real) << " and k " << range_text(domain::index_imag);
  return out.str();
}

Condition parse_fields(const Fields& f) {
  if (f.text().empty()) f.fail("empty condition");
  bool keyword_known = false;
  for (const auto& k : kKinds) {
    if (f[0] != k.keyword) continue;
    keyword_known = true;
    if (!k.matches(f)) continue;
    Condition c = k.parse(f);
    if (!f.swept_field_read()) f.fail("a sweep A..B applies only to a RATE, DIST or VALUE");
    return c;
  }
  if (keyword_known) {
    f.require(2);
    f.fail("unknown " + f[0] + " '" + f[1] + "'");
  }
  f.fail("unknown weather '" + f[0] + "'");
}

// The one field of `fields` that holds a sweep A..B[/STEP][unit].
std::optional<std::size_t> find_sweep(const std::vector<std::string>& fields) {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].find("..") != std::string::npos && fields[i].rfind("file=", 0) != 0) return i;
  return std::nullopt;
}

}  // namespace

const std::string& condition_grammar() {
  static const std::string grammar = generate_grammar();
  return grammar;
}

std::vector<std::string> split_condition_list(const std::string& text) {
  std::vector<std::string> out;
  std::string current;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    const bool continues = std::isdigit(static_cast<unsigned char>(next)) || next == '.' || next == '+' || next == '-';
    if (text[i] == ',' && !continues) {
      if (!current.empty()) out.push_back(current);
      current.clear();
    } else {
      current += text[i];
    }
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

Condition parse_condition(const std::string& text) {
  auto fields = split(text, ':');
  if (find_sweep(fields)) bad(text, "a sweep (A..B) is only allowed in tables");
  return parse_fields(Fields(text, std::move(fields), std::nullopt));
}

std::vector<LabelledCondition> expand_conditions(const std::string& text) {
  const auto fields = split(text, ':');
  const auto at = find_sweep(fields);
  if (!at) return {{text, parse_condition(text)}};
  const std::string& field = fields[*at];
  const auto dots = field.find("..");
  std::string lo_text = field.substr(0, dots), rest = field.substr(dots + 2), step_text = "1", unit;
  // Optional unit suffix (m, km) after the upper bound or the step.
  while (!rest.empty() && std::isalpha(static_cast<unsigned char>(rest.back()))) {
    unit.insert(unit.begin(), rest.back());
    rest.pop_back();
  }
  const auto slash = rest.find('/');
  const std::string hi_text = rest.substr(0, slash);
  if (slash != std::string::npos) step_text = rest.substr(slash + 1);
  double lo = 0, hi = 0, step = 0;
  try {
    lo = io::parse_double(lo_text, "sweep start");
    hi = io::parse_double(hi_text, "sweep end");
    step = io::parse_double(step_text, "sweep step");
  } catch (const std::invalid_argument& e) {
    bad(text, e.what());
  }
  if (!(step > 0) || !(hi >= lo)) bad(text, "sweep A..B/STEP needs A <= B and STEP > 0");
  const double count = std::floor((hi - lo) / step + 1e-9) + 1;
  if (count > 10000) bad(text, "sweep has more than 10000 values");
  std::vector<LabelledCondition> out;
  for (int i = 0; i < static_cast<int>(count); ++i) {
    const double value = lo + i * step;
    // The label: the text as written with the sweep replaced by its value.
    std::ostringstream v;
    v.precision(12);
    v << value << unit;
    auto labelled = fields;
    labelled[*at] = v.str();
    std::string label = labelled[0];
    for (std::size_t j = 1; j < labelled.size(); ++j) label += ":" + labelled[j];
    out.push_back({label, parse_fields(Fields(label, fields, SweptValue{*at, value, unit}))});
  }
  return out;
}

// ---- Back to text -------------------------------------------------------------

namespace {
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
}  // namespace

std::string to_text(const Condition& condition) {
  using io::shortest;
  struct Visitor {
    std::string operator()(const ClearAir& c) const {
      return c.visibility_m ? "clear:" + shortest(*c.visibility_m) + "m" : "clear";
    }
    std::string operator()(const Visibility& c) const { return "visibility:" + shortest(c.visibility_m) + "m"; }
    std::string operator()(const GivenSigma& c) const { return "sigma:" + shortest(c.per_m); }
    std::string operator()(const RainPowerLaw& c) const {
      return "rain:" + shortest(c.rate_mm_h) + ":" + to_string(c.law);
    }
    std::string operator()(const Snow& c) const { return "snow:" + to_string(c.type) + ":" + shortest(c.rate_mm_h); }
    std::string operator()(const FogFromVisibility& c) const {
      return "fog:" + to_string(c.model) + ":" + shortest(c.visibility_m) + "m";
    }
    std::string operator()(const MieCondition& c) const {
      std::string out;
      if (const auto* r = std::get_if<MarshallPalmerRain>(&c.drops)) out = "rain:" + shortest(r->rate_mm_h) + ":mie";
      else if (const auto* p = std::get_if<FogPreset>(&c.drops)) out = "fog:" + to_string(*p);
      else if (const auto* d = std::get_if<ParametricDrops>(&c.drops)) out = drops_text(*d);
      else out = "fog:file=" + std::get<DistributionFile>(c.drops).path;
      if (const auto* t = std::get_if<WaterTable>(&c.index)) out += ":water=" + to_string(*t);
      if (const auto* m = std::get_if<ConstantIndex>(&c.index))
        out += ":m=" + shortest(m->m.real()) + "+" + shortest(m->m.imag()) + "i";
      if (const auto* n = std::get_if<NumberDensity>(&c.rescaling)) out += ":N=" + shortest(n->per_cm3);
      if (const auto* w = std::get_if<LiquidWaterContent>(&c.rescaling)) out += ":lwc=" + shortest(w->g_per_m3);
      return out;
    }
  };
  return std::visit(Visitor{}, condition);
}

}  // namespace attenuvis::weather
