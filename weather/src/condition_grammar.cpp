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
#include "condition_fields.hpp"
#include "registry_rows.hpp"

namespace attenuvis::weather {
namespace {

using detail::bad;
using detail::Fields;
using detail::split;
using detail::SweptValue;


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
  std::string key;  // "m=" ...
  std::string grammar;
  std::string help;
  void (*apply)(MieCondition& c, const std::string& value, const Fields& f);
};

void set_rescaling(MieCondition& c, Rescaling r, const Fields& f) {
  if (!std::holds_alternative<AsGiven>(c.rescaling) && c.rescaling.index() != r.index())
    f.fail("give N= or lwc=, not both");
  c.rescaling = r;
}

// The condition's coating, created unset (NaN) by whichever of coat= and
// shell= comes first; with_options() checks that both came.
Coating& coating_of(MieCondition& c) {
  if (!c.coating) c.coating = Coating{NAN, {NAN, NAN}};
  return *c.coating;
}

// "a|b|c": the names of a registry as the grammar lines write alternatives.
template <class Rows>
std::string alternatives(const Rows& rows) {
  std::string out;
  for (const auto& row : rows) out += (out.empty() ? "" : "|") + row.name;
  return out;
}

const std::vector<MieOption>& mie_options() {
  static const std::vector<MieOption> options = {
      {"m=", ":m=N+Ki | :m=N,K",
       "constant refractive index instead of the water table (m=1.33+0.001i or m=1.33,0.001)",
       [](MieCondition& c, const std::string& v, const Fields& f) { c.index = ConstantIndex{parse_index(v, f)}; }},
      {"water=", ":water=" + alternatives(water_tables()),
       "refractive-index table (ice: " + info(WaterTable::ice).source + "; default: the --water setting)",
       [](MieCondition& c, const std::string& v, const Fields& f) {
         const WaterTableInfo* table = find_water_table(v);
         if (!table) f.fail("water table '" + v + "' is not " + water_table_names());
         c.index = table->id;
       }},
      {"index=", ":index=FILE",
       "refractive index from a file: refractiveindex.info YAML (.yml) or three columns um n k (index_file.hpp)",
       [](MieCondition& c, const std::string& v, const Fields& f) {
         if (v.empty()) f.fail("index= needs a path");
         c.index = IndexFile{v};
       }},
      {"coat=", ":coat=F:shell=N+Ki",
       "core-shell particles: the drops are cores (index m=/water=) under a shell of index shell= that is the "
       "fraction F of each particle's volume (layered-sphere Mie, real-axis quadrature)",
       [](MieCondition& c, const std::string& v, const Fields& f) {
         coating_of(c).shell_volume_fraction = f.in(domain::shell_volume_fraction, v);
       }},
      {"shell=", ":shell=N+Ki", "the shell's refractive index of :coat=",
       [](MieCondition& c, const std::string& v, const Fields& f) { coating_of(c).shell_m = parse_index(v, f); }},
      {"N=", ":N=PER_CM3", "rescale the drops to this many particles per cm^3",
       [](MieCondition& c, const std::string& v, const Fields& f) {
         set_rescaling(c, NumberDensity{f.in(domain::number_density, v)}, f);
       }},
      {"lwc=", ":lwc=G_PER_M3", "rescale the drops to this liquid water content (g/m^3)",
       [](MieCondition& c, const std::string& v, const Fields& f) {
         set_rescaling(c, LiquidWaterContent{f.in(domain::water_content, v)}, f);
       }},
  };
  return options;
}

const MieOption* find_option(const std::string& field) {
  for (const auto& o : mie_options())
    if (field.rfind(o.key, 0) == 0) return &o;
  return nullptr;
}

}  // namespace

MieCondition detail::with_options(Drops drops, const Fields& f, std::size_t from) {
  MieCondition c{std::move(drops), SettingsWaterTable{}, AsGiven{}, std::nullopt};
  for (std::size_t i = from; i < f.size(); ++i) {
    const MieOption* o = find_option(f[i]);
    if (!o) f.fail("unexpected field '" + f[i] + "'");
    std::string value = f[i].substr(o->key.size());
    // A path may itself contain ':'; it runs up to the next option field.
    if (o->key == "index=")
      while (i + 1 < f.size() && !find_option(f[i + 1])) value += ":" + f[++i];
    o->apply(c, value, f);
  }
  if (c.coating && std::isnan(c.coating->shell_volume_fraction)) f.fail("shell= needs coat=F (the shell's volume fraction)");
  if (c.coating && std::isnan(c.coating->shell_m.real())) f.fail("coat= needs shell=N+Ki (the shell's index)");
  return c;
}

namespace {

// ---- The kinds --------------------------------------------------------------

struct Kind {
  std::string keyword;
  std::string grammar;  // the grammar line
  std::string help;
  bool (*matches)(const Fields& f);  // among the kinds that share a keyword
  Condition (*parse)(const Fields& f);
};

bool always(const Fields&) { return true; }
bool family_is(const Fields& f, const char* name) { return f.size() >= 2 && f[1] == name; }

// "fog:advection | fog:radiation | ": one alternative per fog preset.
std::string fog_preset_lines() {
  std::string out;
  for (const auto& p : fog_presets()) out += "fog:" + p.name + " | ";
  return out;
}

// "snow:wet:RATE | snow:dry:RATE".
std::string snow_lines() {
  std::string out;
  for (const auto& t : snow_types()) out += std::string(out.empty() ? "" : " | ") + "snow:" + t.name + ":RATE";
  return out;
}

// The default rain law (the first) and its coefficients: "seed (default): k=1.17, alpha=0.65".
std::string default_rain_law_text() {
  const RainLawCoefficients& law = rain_power_laws().front();
  return law.name + " (default): k=" + io::shortest(law.k) + ", alpha=" + io::shortest(law.alpha);
}

Condition parse_rain_power_law(const Fields& f) {
  f.require(2);
  const double rate = f.rate(1, domain::rain_rate);
  if (f.size() < 3) return RainPowerLaw{rate, rain_power_laws().front().law};
  f.at_most(3, "options (m=, N=...) apply only to rain:RATE:mie");
  try {
    return RainPowerLaw{rate, rain_power_law(f[2]).law};
  } catch (const std::invalid_argument&) {
    std::string names;
    for (const auto& l : rain_power_laws()) names += l.name + ", ";
    f.fail("unknown rain model '" + f[2] + "' (" + names + "or mie)");
  }
}

Condition parse_snow(const Fields& f) {
  f.require(3);
  const SnowTypeInfo* type = find_snow_type(f[1]);
  if (!type) f.fail("snow type must be " + detail::name_list(detail::names_of(snow_types())));
  f.at_most(3, "snow takes a type and a rate");
  return Snow{type->id, f.rate(2, domain::snow_rate)};
}

Condition parse_mie_fog(const Fields& f) {
  if (const FogPresetInfo* preset = find_fog_preset(f[1])) return with_options(preset->id, f, 2);
  // A path may itself contain ':'; it runs up to the first option field.
  std::string path = f[1].substr(5);
  std::size_t i = 2;
  while (i < f.size() && !find_option(f[i])) path += ":" + f[i++];
  if (path.empty()) f.fail("fog:file= needs a path");
  return with_options(DistributionFile{path}, f, i);
}

Condition parse_empirical_fog(const Fields& f) {
  f.require(3);
  f.at_most(3, "empirical fog takes one visibility");
  return FogFromVisibility{find_visibility_fog_model(f[1])->id, f.distance(2)};
}

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> table = {
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
       [](const Fields& f) -> Condition {
         return with_options(MarshallPalmerRain{f.rate(1, domain::rain_rate)}, f, 3);
       }},
      {"rain", "rain:RATE[:" + alternatives(rain_power_laws()) + "]",
       "power law, RATE mm/h, read per --convention; " + default_rain_law_text() + "; e.g. rain:8", always,
       parse_rain_power_law},
      {"snow", snow_lines(), "P.1817-1 a(lambda) S^b, RATE mm/h, read per --convention", always, parse_snow},
      {"fog", fog_preset_lines() + "fog:file=PATH  [:OPTIONS]",
       "Mie over the P.1817-1 / seed modified-gamma presets or a size-distribution CSV",
       [](const Fields& f) {
         return f.size() >= 2 && (find_fog_preset(f[1]) != nullptr || f[1].rfind("file=", 0) == 0);
       },
       parse_mie_fog},
      {"drops", "drops:lognormal:r=RADIUS:sg=SG  [:OPTIONS]",
       "Mie over a log-normal: median radius, geometric std. dev. SG in (1, 20]; needs N= or lwc=",
       [](const Fields& f) { return family_is(f, "lognormal"); }, detail::parse_lognormal_drops},
      {"drops", "drops:gamma:r=RADIUS:alpha=A  [:OPTIONS]",
       "Mie over a gamma n ~ r^A exp(-A r/RADIUS): mode radius, shape A in (0, 100]; needs N= or lwc=",
       [](const Fields& f) { return family_is(f, "gamma"); }, detail::parse_gamma_drops},
      {"drops", "drops:mgamma:a=A:alpha=AL:b=B[:gamma=G] | drops:mgamma:rc=RADIUS:alpha=AL[:gamma=G]",
       "Mie over Deirmendjian's n = A r^AL exp(-B r^G), r in um, n in cm^-3 um^-1 (G = 1 by default); "
       "with rc= (mode radius, B = AL/(G rc^G)) it needs N= or lwc=",
       [](const Fields& f) { return family_is(f, "mgamma"); }, detail::parse_mgamma_drops},
      {"drops", "drops:exponential:n0=N0:lambda=L  [:OPTIONS]",
       "Mie over N(D) = N0 exp(-L D) in diameter D: N0 in m^-3 mm^-1, L in mm^-1 (Marshall & Palmer form)",
       [](const Fields& f) { return family_is(f, "exponential"); }, detail::parse_exponential_drops},
      {"drops", "drops:powerlaw:nu=NU:rmin=RADIUS:rmax=RADIUS  [:OPTIONS]",
       "Mie over a Junge power law n ~ r^-NU on [rmin, rmax]; needs N= or lwc=",
       [](const Fields& f) { return family_is(f, "powerlaw"); }, detail::parse_powerlaw_drops},
      {"fog", "fog:" + alternatives(visibility_fog_models()) + ":DIST", "empirical fog from visibility DIST",
       [](const Fields& f) { return f.size() >= 2 && find_visibility_fog_model(f[1]) != nullptr; },
       parse_empirical_fog},
      {"haze", "haze:TYPE:rh=RH  [:AEROSOL OPTIONS]",
       "OPAC aerosol type (Hess et al. 1998, Table 4) at relative humidity RH %; TYPE " +
           alternatives(aerosol_mixtures()),
       always, detail::parse_haze},
      {"aerosol", "aerosol:COMP=N[,COMP=N...]:rh=RH  [:AEROSOL OPTIONS]",
       "external mixture of OPAC components, N per cm^3; COMP " + alternatives(aerosol_components()), always,
       detail::parse_aerosol},
  };
  return table;
}

std::string generate_grammar() {
  std::size_t width = 0;
  for (const auto& k : kinds()) width = std::max(width, k.grammar.size());
  for (const auto& o : mie_options()) width = std::max(width, o.grammar.size() + 2);
  for (const auto& o : detail::aerosol_option_help()) width = std::max(width, o.first.size() + 2);
  std::ostringstream out;
  const auto line = [&](const std::string& left, const std::string& right) {
    out << "  " << left << std::string(width + 2 - left.size(), ' ') << right << "\n";
  };
  out << "conditions:\n";
  for (const auto& k : kinds()) line(k.grammar, k.help);
  out << "  OPTIONS after a Mie condition (fog:..., rain:RATE:mie, drops:...), any order:\n";
  for (const auto& o : mie_options()) line("  " + o.grammar, o.help);
  out << "  AEROSOL OPTIONS after haze:... or aerosol:..., any order:\n";
  for (const auto& [grammar, help] : detail::aerosol_option_help()) line("  " + grammar, help);
  out << "  RATE in mm/h; DIST a number with unit " << distance_units() << " (bare number: m), e.g. 500m, 2km\n"
      << "  in tables a RATE, DIST, VALUE or rh= may sweep: A..B or A..B/STEP (rain:1..100, fog:kim:200..1000/200m,\n"
      << "  haze:urban:rh=0..99/9);\n"
      << "  a sweep ends at B (rain:1..100/10: 1, 11, ..., 91, 100)\n"
      << "  valid ranges: rain RATE " << range_text(domain::rain_rate) << ", snow RATE "
      << range_text(domain::snow_rate) << ", DIST " << range_text(domain::visibility) << ",\n"
      << "    sigma VALUE " << range_text(domain::sigma) << " (in any unit), N= " << range_text(domain::number_density)
      << ", lwc= " << range_text(domain::water_content) << ",\n"
      << "    m= and shell= n " << range_text(domain::index_real) << " and k " << range_text(domain::index_imag)
      << ", coat= " << range_text(domain::shell_volume_fraction) << ",\n"
      << "    rh= " << range_text(domain::relative_humidity) << ", mass= " << range_text(domain::aerosol_mass)
      << ", an aerosol's N " << range_text(domain::number_density);
  return out.str();
}

Condition parse_fields(const Fields& f) {
  if (f.text().empty()) f.fail("empty condition");
  bool keyword_known = false;
  for (const auto& k : kinds()) {
    if (f[0] != k.keyword) continue;
    keyword_known = true;
    if (!k.matches(f)) continue;
    Condition c = k.parse(f);
    if (!f.swept_field_read()) f.fail("a sweep A..B applies only to a RATE, DIST, VALUE, rh= or visibility=");
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
    if (fields[i].find("..") != std::string::npos && fields[i].rfind("file=", 0) != 0 &&
        fields[i].rfind("index=", 0) != 0)
      return i;
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
    // ... and a comma before a component's "NAME=" continues an aerosol's list (aerosol:waso=7000,soot=8300).
    const bool continues = std::isdigit(static_cast<unsigned char>(next)) || next == '.' || next == '+' ||
                           next == '-' || detail::starts_with_component(text, i + 1);
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
  // A keyed field (rh=0..99/10) keeps its key in the labels.
  const std::size_t eq = fields[*at].find('=');
  const std::string key = eq != std::string::npos && eq < fields[*at].find("..") ? fields[*at].substr(0, eq + 1) : "";
  const std::string field = fields[*at].substr(key.size());
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
  // A, A + STEP, ... below B, then B itself: a sweep ends where it says.  A
  // grid point within 1e-6 STEP of B (decimal steps such as 0.1 are not exact
  // in binary) is B; where B is off the grid the last step is shorter.
  const double below = std::ceil((hi - lo) / step - 1e-6);  // grid points before B
  if (below + 1 > 10000) bad(text, "sweep has more than 10000 values");
  const int count = static_cast<int>(below) + 1;
  std::vector<LabelledCondition> out;
  for (int i = 0; i < count; ++i) {
    const double value = i + 1 == count ? hi : lo + i * step;
    // The label: the text as written with the sweep replaced by its value.
    std::ostringstream v;
    v.precision(12);
    v << key << value << unit;
    auto labelled = fields;
    labelled[*at] = v.str();
    std::string label = labelled[0];
    for (std::size_t j = 1; j < labelled.size(); ++j) label += ":" + labelled[j];
    out.push_back({label, parse_fields(Fields(label, fields, SweptValue{*at, value, unit}))});
  }
  return out;
}

// ---- Back to text -------------------------------------------------------------


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
      else if (const auto* d = std::get_if<ParametricDrops>(&c.drops)) out = detail::drops_text(*d);
      else out = "fog:file=" + std::get<DistributionFile>(c.drops).path;
      if (const auto* t = std::get_if<WaterTable>(&c.index)) out += ":water=" + to_string(*t);
      if (const auto* m = std::get_if<ConstantIndex>(&c.index))
        out += ":m=" + shortest(m->m.real()) + "+" + shortest(m->m.imag()) + "i";
      if (const auto* file = std::get_if<IndexFile>(&c.index)) out += ":index=" + file->path;
      if (const auto* n = std::get_if<NumberDensity>(&c.rescaling)) out += ":N=" + shortest(n->per_cm3);
      if (const auto* w = std::get_if<LiquidWaterContent>(&c.rescaling)) out += ":lwc=" + shortest(w->g_per_m3);
      if (c.coating)
        out += ":coat=" + shortest(c.coating->shell_volume_fraction) + ":shell=" +
               shortest(c.coating->shell_m.real()) + "+" + shortest(c.coating->shell_m.imag()) + "i";
      return out;
    }
    std::string operator()(const AerosolCondition& c) const { return detail::aerosol_text(c); }
  };
  return std::visit(Visitor{}, condition);
}

}  // namespace attenuvis::weather
